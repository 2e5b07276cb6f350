// lightsolver.verify_results: the comparison `lightsolver verify` makes, for a results dict.
#include "provenance_bindings.hpp"

#include <pybind11/stl.h>

#include <string>

#include "lightsolver/provenance.hpp"

namespace py = pybind11;

void bind_provenance(py::module_& m) {
  m.def(
      "verify_results",
      [](const std::string& scene_path, const py::dict& results) {
        // Only the provenance is read: the dict may hold numpy arrays or an older layout.
        const py::object p = results.attr("get")("provenance");
        const std::string text = py::str(py::module_::import("json").attr("dumps")(p));
        return lightsolver::verify_provenance(scene_path,
                                              lightsolver::provenance_from_json(text, "results"));
      },
      py::arg("scene_path"), py::arg("results"),
      "Why `results` (a results dict) do not belong to the scene file `scene_path`, one sentence "
      "per difference: the scene's content changed, a file it reads (mesh, photometric file, "
      "requirements table) changed, is missing, new or no longer read; results without "
      "provenance, or traced from a scene built in memory, 'cannot be verified'. Empty: they "
      "belong together (`lightsolver verify`). Raises InputError for a scene file that cannot "
      "be read or parsed, or a malformed provenance.");
}
