// lightsolver.verify_results and lightsolver.verify_document: the comparison `lightsolver
// verify` makes, for a results dict or an optimizer's output dict.
#include "provenance_bindings.hpp"

#include <pybind11/stl.h>

#include <string>

#include "lightsolver/provenance.hpp"

namespace py = pybind11;

namespace {

// What the comparison reads of a document (a results dict may hold numpy arrays or an older
// layout): its format, provenance and flux record, as JSON text.
lightsolver::Verification verify_dict(const std::string& scene_path, const py::dict& doc) {
  py::dict part;
  for (const char* key : {"format", "provenance", "rescaled", "groups", "luminaires"}) {
    if (doc.contains(key)) part[key] = doc[key];
  }
  const std::string text = py::str(py::module_::import("json").attr("dumps")(part));
  return lightsolver::verify_document(scene_path, text, "results", /*validate=*/false);
}

}  // namespace

void bind_provenance(py::module_& m) {
  m.def(
      "verify_results",
      [](const std::string& scene_path, const py::dict& results) {
        return verify_dict(scene_path, results).differences;
      },
      py::arg("scene_path"), py::arg("results"),
      "Why `results` (a results dict, or an optimizer's output dict) do not belong to the scene "
      "file `scene_path`, one sentence per difference: the scene's content changed, a file it "
      "reads (mesh, photometric file, requirements table) changed, is missing, new or no longer "
      "read; a flux record that is not the solver's (a luminaire's dimming not its group's "
      "`rescaled` factor, a group's flux not its luminaires' sum); an optimizer's output of "
      "another optimization block; results without provenance, or traced from a scene built in "
      "memory, 'cannot be verified'. Empty: they belong together (`lightsolver verify`). Raises "
      "InputError for a scene file that cannot be read or parsed, or a malformed provenance.");
  m.def(
      "verify_document",
      [](const std::string& scene_path, const py::dict& doc) {
        const lightsolver::Verification v = verify_dict(scene_path, doc);
        py::dict out;
        out["differences"] = v.differences;
        out["notes"] = v.notes;
        out["optimization"] = v.optimization;
        return out;
      },
      py::arg("scene_path"), py::arg("document"),
      "verify_results() with what `lightsolver verify` prints beside it: a dict with "
      "`differences` (empty: the document belongs to the scene), `notes` (when it belongs: the "
      "groups rescaled from the scene's fluxes with their factors; that an optimizer's output "
      "holds configurations, not results) and `optimization` (the document is an optimizer's "
      "output).");
}
