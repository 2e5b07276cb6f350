// Python binding of the inverse-lighting search: lightsolver.optimize(scene or path, ...) runs
// the scene's optimization block (or one given as a dict) with the GIL released, calls
// `progress` after every iteration and returns the result JSON as a dict.
#include <pybind11/functional.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <optional>
#include <thread>

#include "lightsolver/optimizer/scene_problem.hpp"
#include "lightsolver/scene_io.hpp"
#include "run_option_keywords.hpp"

namespace py = pybind11;
namespace opt = lightsolver::optimizer;

namespace {

py::dict stats_dict(const opt::IterationStats& s, const char* event) {
  py::dict d;
  d["event"] = event;
  d["iteration"] = s.iteration;
  d["evaluations"] = s.total_evaluations;
  d["elapsed_seconds"] = s.elapsed_seconds;
  d["k"] = s.k;
  d["isoc_size"] = s.isoc_size;
  d["total_photons"] = s.total_photons;
  d["update_seconds"] = s.update_seconds;
  d["trace_seconds"] = s.trace_seconds;
  d["other_seconds"] = s.other_seconds;
  if (s.has_best) {
    d["best"] = py::make_tuple(s.best.mean, s.best.ci_low, s.best.ci_high);
  } else {
    d["best"] = py::none();
  }
  return d;
}

// Mirrors a CancelToken (a Python object, read under the GIL) into the engine's atomic flag,
// which it polls before every trace; so a cancel() from another Python thread takes effect
// within one trace plus one polling period. Constructed and destroyed without the GIL.
class CancelWatcher {
 public:
  CancelWatcher(py::object token, std::atomic<bool>& stop) : stop_(stop) {
    if (token.is_none()) return;
    token_ = std::move(token);
    thread_ = std::thread([this] { watch(); });
  }
  ~CancelWatcher() {
    if (!thread_.joinable()) return;
    done_.store(true);
    thread_.join();
    py::gil_scoped_acquire gil;
    token_ = py::object();  // dropped with the GIL held
  }

 private:
  void watch() {
    while (!done_.load() && !stop_.load()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      py::gil_scoped_acquire gil;
      if (token_.attr("cancelled").cast<bool>()) stop_.store(true);
    }
  }
  std::atomic<bool>& stop_;
  std::atomic<bool> done_{false};
  py::object token_;
  std::thread thread_;
};

opt::SceneProblem problem_from(py::object scene, py::object optimization) {
  py::object dumps = py::module_::import("json").attr("dumps");
  if (py::isinstance<py::str>(scene) || py::hasattr(scene, "__fspath__")) {
    const std::string path = py::str(py::module_::import("os").attr("fspath")(scene));
    if (optimization.is_none()) return opt::load_problem(path);
    // The given block replaces the file's, which is neither read nor required.
    return opt::problem_from_scene(lightsolver::load_scene(path),
                                   dumps(optimization).cast<std::string>(), path);
  }
  if (optimization.is_none()) {
    throw py::value_error(
        "optimize(): a Scene object needs optimization={...} (the block as a "
        "dict, see docs/optimization.md)");
  }
  return opt::problem_from_scene(scene.cast<lightsolver::Scene>(),
                                 dumps(optimization).cast<std::string>());
}

py::dict optimize_py(py::object scene, py::object optimization,
                     std::optional<std::uint64_t> iterations, std::optional<std::uint64_t> seed,
                     std::optional<std::uint64_t> screening_photons,
                     std::optional<std::uint64_t> confirmation_photons, int threads,
                     py::object progress, py::object cancel, const std::string& backend,
                     std::optional<bool> reuse_traces, std::optional<std::string> next_event,
                     std::optional<std::uint64_t> refine_stage_photons,
                     std::optional<bool> match_widths) {
  const opt::SceneProblem problem = problem_from(scene, optimization);
  opt::RunOverrides o{iterations, seed, screening_photons, confirmation_photons, threads, backend};
  o.reuse_traces = reuse_traces;
  o.next_event = std::move(next_event);
  o.refine_stage_photons = refine_stage_photons;
  o.match_widths = match_widths;
  o.command = python_command("optimize");
  std::atomic<bool> stop{false};
  opt::Control control;
  control.cancel = &stop;
  std::optional<py::error_already_set> failure;
  if (!progress.is_none()) {
    auto call = [&](const opt::IterationStats& s, const char* event) {
      py::gil_scoped_acquire gil;
      try {
        py::object r = progress(stats_dict(s, event));
        return r.is_none() || r.cast<bool>();
      } catch (py::error_already_set& e) {
        failure = std::move(e);  // re-raised once the search has stopped
        return false;
      }
    };
    control.progress = [call](const opt::IterationStats& s) { return call(s, "iteration"); };
    // Every trace, at most 4 times a second (synthetic or tiny scenes trace in microseconds):
    // an iteration's descent may take minutes, and the caller wants progress within seconds.
    auto last = std::make_shared<double>(-1.0);
    control.on_evaluation = [call, last](const opt::IterationStats& s) {
      if (*last >= 0.0 && s.elapsed_seconds - *last < 0.25) return true;
      *last = s.elapsed_seconds;
      return call(s, "evaluation");
    };
  }
  std::string json;
  {
    py::gil_scoped_release nogil;
    CancelWatcher watcher(cancel, stop);
    const opt::OptimizationResult r = opt::run_problem(problem, o, control);
    json = opt::problem_result_json(problem, r, -1);
  }
  if (failure) throw std::move(*failure);
  return py::module_::import("json").attr("loads")(json);
}

}  // namespace

void bind_optimizer(py::module_& m) {
  m.def("optimize", &optimize_py, py::arg("scene"), py::arg("optimization") = py::none(),
        py::arg("iterations") = py::none(), py::arg("seed") = py::none(),
        py::arg("screening_photons") = py::none(), py::arg("confirmation_photons") = py::none(),
        py::arg("threads") = 0, py::arg("progress") = py::none(), py::arg("cancel") = py::none(),
        py::arg("backend") = lightsolver::kAutoBackend, py::arg("reuse_traces") = py::none(),
        py::arg("next_event") = py::none(), py::arg("refine_stage_photons") = py::none(),
        py::arg("match_widths") = py::none(),
        R"(Search a scene's optimization block for the best configurations.

scene: a scene file path (its "optimization" block is used unless `optimization` is given) or a
    Scene (then `optimization` is required: the block as a dict, docs/optimization.md).
iterations, seed, screening_photons (n), confirmation_photons (N): override the block's search.
progress: called with a dict after every iteration (event="iteration") and after traces
    (event="evaluation", at most 4 times a second): iteration (completed), evaluations (so
    far), elapsed_seconds, k, best=(mean, lo, hi) or None, isoc_size, total_photons,
    update_seconds, trace_seconds, other_seconds; return False to stop.
cancel: a CancelToken; cancel() from another thread stops the search within one trace.
backend: a name from backends() ("auto": a real GPU when one is usable, else Embree).
reuse_traces: overrides search.reuse_traces (default true: each luminaire group traced apart and
    its trace kept for configurations that do not change it; a flux level traces nothing).
next_event: "auto", "on" or "off": overrides the scene's settings.next_event for every
    evaluation (direct light at the targets by shadow rays, docs/optimization.md §9).
refine_stage_photons: overrides search.refine_stage_photons (the staged end refinement's first
    stage, N1 photons of each member's N stream; 0: unstaged).
match_widths: overrides search.match_widths (default True: with next-event estimation, N and
    the stages scaled down to the interval width a photon-only search has at N; provenance
    width_factor; False keeps N as given).
Returns the result as a dict (format lightsolver.optimization/1): isoc members with cells,
values, objective and constraint estimates and "scene" (world positions), siisoc, counters,
history. The GIL is released while searching.)");
}
