// Python binding of lightsolver::Simulation: a scene loaded and prepared once, then changed
// (a luminaire, a movable mesh's placement) and traced again, or traced further (refine) from
// the photons already traced. Tracing releases the GIL; one call at a time runs on a simulation
// (a mutex), and cancel() from any thread stops the one in progress after its current batch.
#include "simulation_bindings.hpp"

#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <atomic>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>

#include "lightsolver/scene_io.hpp"
#include "lightsolver/simulation.hpp"
#include "run_option_keywords.hpp"

namespace py = pybind11;
using namespace lightsolver;

namespace {

class PySimulation {
 public:
  PySimulation(py::object scene, const std::string& backend, int threads,
               std::vector<std::string> movable_meshes) {
    Scene s = scene_from(scene);
    base_dir_ = s.source_file.empty() ? std::string(".")
                                      : std::filesystem::path(s.source_file).parent_path().string();
    if (base_dir_.empty()) base_dir_ = ".";
    Simulation::Options o;
    o.backend = backend;
    o.threads = threads;
    o.movable_meshes = std::move(movable_meshes);
    py::gil_scoped_release nogil;  // building the backend (BVH, device) takes a while
    sim_ = std::make_unique<Simulation>(std::move(s), std::move(o));
  }

  // `fields`: a scene file's luminaire entry (docs/scene-format.md); "name" defaults to the
  // current luminaire's. Photometric files are relative to the scene file's folder.
  void set_luminaire(std::size_t index, const py::dict& fields) {
    const std::string where = "set_luminaire(" + std::to_string(index) + ")";
    nlohmann::json entry = to_json(fields, where);
    std::lock_guard lock(locked(mutex_), std::adopt_lock);
    const Scene& s = sim_->scene();
    if (index >= s.luminaires.size()) {
      throw InputError(s.source_file, "luminaires", "no luminaire " + std::to_string(index));
    }
    if (!entry.contains("name")) entry["name"] = s.luminaires[index].name;
    sim_->set_luminaire(index, luminaire_from_json(entry, where, base_dir_));
  }

  // `matrix`: 4x4, row-major as written on paper (translation in the last column).
  void set_mesh_transform(std::size_t mesh,
                          py::array_t<double, py::array::c_style | py::array::forcecast> matrix) {
    if (matrix.ndim() != 2 || matrix.shape(0) != 4 || matrix.shape(1) != 4) {
      throw InputError("", "meshes[" + std::to_string(mesh) + "]", "transform must be 4x4");
    }
    glm::dmat4 m(1.0);
    auto a = matrix.unchecked<2>();
    for (int row = 0; row < 4; ++row) {
      for (int col = 0; col < 4; ++col) m[col][row] = a(row, col);  // glm is column-major
    }
    std::lock_guard lock(locked(mutex_), std::adopt_lock);
    sim_->set_mesh_transform(mesh, m);
  }

  // `o`: the run options of the call (run_option_keywords); `progress` as solve() takes it.
  py::dict run(SolveOptions o, const py::object& progress, bool refine) {
    o.cancel = &cancel_;
    std::exception_ptr callback_error;
    const ProgressFn fn = python_progress(progress, callback_error);
    Results r;
    {
      std::lock_guard lock(locked(mutex_), std::adopt_lock);
      py::gil_scoped_release nogil;
      cancel_.store(false);
      r = refine ? sim_->refine(o, fn) : sim_->run(o, fn);
    }
    if (callback_error) std::rethrow_exception(callback_error);
    return results_dict(r);
  }

  // Group `group` traced alone (Simulation::trace_group): its share of a run of `photons`.
  std::shared_ptr<GroupTrace> trace_group(std::size_t group, std::uint64_t photons,
                                          std::uint64_t seed) {
    std::lock_guard lock(locked(mutex_), std::adopt_lock);
    py::gil_scoped_release nogil;
    return std::make_shared<GroupTrace>(sim_->trace_group(group, photons, seed));
  }

  // `traces[g]`: group g's trace or None (dark); the results record the call as its command.
  py::dict combine(const py::list& traces, const std::vector<double>& flux_lm, double confidence) {
    std::vector<const GroupTrace*> parts;
    for (const py::handle t : traces) {
      parts.push_back(t.is_none() ? nullptr : &t.cast<const GroupTrace&>());
    }
    const std::string command = python_command("combine");
    Results r;
    {
      std::lock_guard lock(locked(mutex_), std::adopt_lock);
      py::gil_scoped_release nogil;
      r = sim_->combine(parts, flux_lm, confidence);
    }
    if (r.provenance) r.provenance->command = command;
    return results_dict(r);
  }

  py::list groups() {
    std::lock_guard lock(locked(mutex_), std::adopt_lock);
    py::list out;
    for (const LuminaireGroup& g : sim_->groups()) {
      py::dict d;
      d["name"] = g.name;
      d["flux_lm"] = g.flux_lm;
      d["luminaires"] = g.luminaires;
      out.append(d);
    }
    return out;
  }

  void cancel() { cancel_.store(true); }

  std::uint64_t kept_photons() {
    std::lock_guard lock(locked(mutex_), std::adopt_lock);
    return sim_->kept_photons();
  }

  std::vector<std::string> luminaire_names() {
    std::lock_guard lock(locked(mutex_), std::adopt_lock);
    std::vector<std::string> names;
    for (const Luminaire& l : sim_->scene().luminaires) names.push_back(l.name);
    return names;
  }

  std::vector<std::string> mesh_names() {
    std::lock_guard lock(locked(mutex_), std::adopt_lock);
    std::vector<std::string> names;
    for (const Mesh& m : sim_->scene().meshes) names.push_back(m.name);
    return names;
  }

 private:
  static Scene scene_from(const py::object& scene) {
    if (py::isinstance<py::str>(scene) || py::hasattr(scene, "__fspath__")) {
      return load_scene(py::str(py::module_::import("os").attr("fspath")(scene)));
    }
    return scene.cast<Scene>();  // a copy: the Python object may change later
  }

  // Waits for the mutex without the GIL (a run in another thread holds it while tracing and
  // takes the GIL for progress callbacks), then returns it locked (for a lock_guard that adopts
  // it).
  static std::mutex& locked(std::mutex& m) {
    py::gil_scoped_release nogil;
    m.lock();
    return m;
  }

  std::mutex mutex_;
  std::atomic<bool> cancel_{false};
  std::unique_ptr<Simulation> sim_;
  std::string base_dir_;
};

// refine() takes run()'s keywords but photons (photons_total instead) and decide.
bool refine_keyword(const RunOptionInfo& row) {
  return per_run_keyword(row) && std::string_view(row.name) != "photons" &&
         std::string_view(row.name) != "decide";
}

py::object progress_of(const py::kwargs& keywords) {
  return keywords.contains("progress") ? py::object(keywords["progress"]) : py::object(py::none());
}

}  // namespace

void bind_simulation(py::module_& m) {
  py::class_<GroupTrace, std::shared_ptr<GroupTrace>>(
      m, "GroupTrace",
      "One luminaire group's tallies, traced alone by Simulation.trace_group and summed into "
      "results by Simulation.combine (docs/optimization.md, \"Reused traces\")")
      .def_readonly("group", &GroupTrace::group)
      .def_readonly("run_photons", &GroupTrace::run_photons)
      .def_readonly("photons", &GroupTrace::photons)
      .def_readonly("seed", &GroupTrace::seed);
  py::class_<PySimulation>(m, "Simulation",
                           "A scene prepared once for many runs with small changes between them "
                           "(docs/live.md): set_luminaire, set_mesh_transform, run, refine")
      .def(py::init<py::object, const std::string&, int, std::vector<std::string>>(),
           py::arg("scene"), py::arg("backend") = "auto", py::arg("threads") = 0,
           py::arg("movable_meshes") = std::vector<std::string>{},
           "scene: a Scene or a scene file's path (copied). movable_meshes: names of the meshes "
           "set_mesh_transform may move. Raises InputError for a bad scene or name.")
      .def("set_luminaire", &PySimulation::set_luminaire, py::arg("index"), py::arg("fields"),
           "Replaces luminaire `index` with a scene file's luminaire entry given as a dict "
           "(type and its keys; name defaults to the current one's). Discards the photons kept "
           "for refine(). A rejected entry (InputError) leaves the simulation as it was.")
      .def("set_mesh_transform", &PySimulation::set_mesh_transform, py::arg("index"),
           py::arg("matrix"),
           "Places movable mesh `index` with a rigid 4x4 world transform (row-major, translation "
           "in the last column) applied to its coordinates as loaded. Discards the kept photons.")
      .def(
          "run",
          [](PySimulation& s, const py::kwargs& keywords) {
            SolveOptions o;
            set_run_options(keywords, o, per_run_keyword, {"progress"}, "run");
            return s.run(std::move(o), progress_of(keywords), false);
          },
          ("Traces from photon 0 as lightsolver.solve() would (same keywords but the backend's, "
           "same results dict); the tallies are kept for refine(). Keywords:" +
           keywords_doc(per_run_keyword) + "\n  progress=None: as solve()'s")
              .c_str())
      .def(
          "refine",
          [](PySimulation& s, std::uint64_t photons_total, const py::kwargs& keywords) {
            SolveOptions o;
            set_run_options(keywords, o, refine_keyword, {"progress"}, "refine");
            o.photons = photons_total;
            return s.run(std::move(o), progress_of(keywords), true);
          },
          py::arg("photons_total"),
          ("Continues the kept photons up to photons_total in all: the same results, bit for "
           "bit, as run(photons=photons_total). Starts at photon 0 after a change, with another "
           "seed, or when more photons are kept. Never decides (verdicts are judged as in run). "
           "Keywords:" +
           keywords_doc(refine_keyword) + "\n  progress=None: as solve()'s")
              .c_str())
      .def_property_readonly(
          "groups", &PySimulation::groups,
          "The luminaire groups as the scene stands: dicts with name, flux_lm (emitted) and "
          "luminaires (indices), in the order of their first luminaire")
      .def("trace_group", &PySimulation::trace_group, py::arg("group"), py::arg("photons"),
           py::arg("seed"),
           "Traces luminaire group `group` alone: its share of a run of `photons` photons with "
           "`seed`, equal bit for bit to that group's part of run(photons=..., seed=...). Returns "
           "a GroupTrace for combine(). Raises InputError for an unknown or dark group.")
      .def("combine", &PySimulation::combine, py::arg("traces"), py::arg("flux_lm"),
           py::arg("confidence") = 0.95,
           "Results (a dict as run() returns) from groups traced apart: traces[g] is group g's "
           "GroupTrace or None (dark), flux_lm[g] the flux it emits now (its tallies are scaled "
           "to it). Records every group's factor against the scene's flux in `rescaled` and a "
           "provenance as run() does (docs/scene-format.md, \"Provenance\"): "
           "lightsolver.verify_results accepts them for the scene file when it is unchanged.")
      .def("cancel", &PySimulation::cancel,
           "Stops the run in progress (any thread) after its current batch; its result is "
           "partial and its photons are kept")
      .def_property_readonly("kept_photons", &PySimulation::kept_photons,
                             "Photons refine() continues from (0 after a change)")
      .def_property_readonly("luminaire_names", &PySimulation::luminaire_names)
      .def_property_readonly("mesh_names", &PySimulation::mesh_names);
}
