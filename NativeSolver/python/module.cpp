// Python bindings: the same scenes and results as the CLI, numpy in and out, the GIL released
// while tracing, progress callbacks and cancellation.
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <cmath>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>

#include "daylight_bindings.hpp"
#include "direct_sun_bindings.hpp"
#include "lightsolver/backends.hpp"
#include "lightsolver/cost.hpp"
#include "lightsolver/defaults.hpp"
#include "lightsolver/glare.hpp"
#include "lightsolver/mpi.hpp"
#include "lightsolver/photometry.hpp"
#include "lightsolver/rescale.hpp"
#include "lightsolver/scene_check.hpp"
#include "lightsolver/scene_io.hpp"
#include "lightsolver/solver.hpp"
#include "lightsolver/study.hpp"
#include "optimize_bindings.hpp"
#include "provenance_bindings.hpp"
#include "run_option_keywords.hpp"
#include "scene_bindings.hpp"
#include "simulation_bindings.hpp"
#include "sky_patches_bindings.hpp"
#include "annual_bindings.hpp"
#include "types_bindings.hpp"

namespace py = pybind11;
using namespace lightsolver;

namespace {

struct CancelToken {
  std::shared_ptr<std::atomic<bool>> flag = std::make_shared<std::atomic<bool>>(false);
  void cancel() { flag->store(true); }
  bool cancelled() const { return flag->load(); }
};

// {type: {key: default}} for the keys a scene file may leave out (docs/scene-format.md).
py::dict material_defaults_dict() {
  using T = Material::Type;
  const Material diffuse = default_material("", T::Diffuse),
                 mirror = default_material("", T::Mirror), glass = default_material("", T::Glass),
                 glossy = default_material("", T::Glossy);
  py::dict d;
  d["diffuse"] = py::dict(py::arg("reflectance") = diffuse.reflectance);
  d["mirror"] = py::dict(py::arg("reflectance") = mirror.reflectance);
  d["glass"] = py::dict(py::arg("ior") = glass.ior, py::arg("transmittance") = glass.transmittance,
                        py::arg("thin") = glass.thin);
  d["glossy"] =
      py::dict(py::arg("reflectance") = glossy.reflectance, py::arg("specular") = glossy.specular,
               py::arg("roughness") = glossy.roughness);
  return d;
}

// {"errors": [...], "warnings": [...]}, each issue a dict with field, file, line, message.
py::dict check_dict(const SceneCheck& check) {
  const auto issues = [](const std::vector<SceneIssue>& list) {
    py::list out;
    for (const SceneIssue& i : list) {
      out.append(py::dict(py::arg("field") = i.field, py::arg("file") = i.file,
                          py::arg("line") = i.line, py::arg("message") = i.message));
    }
    return out;
  };
  return py::dict(py::arg("errors") = issues(check.errors),
                  py::arg("warnings") = issues(check.warnings));
}

// A photometric file's facts as a dict; NaN angles (never falling that low) become None.
py::dict photometry_summary_dict(const std::string& path) {
  const PhotometricData data = load_photometry(path);
  const PhotometryFacts f = photometry_facts(data);
  const auto angle = [](double deg) -> py::object {
    return std::isfinite(deg) ? py::object(py::float_(deg)) : py::object(py::none());
  };
  py::dict d;
  d["file"] = data.source_file;
  d["format"] = data.format == PhotometricFormat::Ies ? "ies" : "ldt";
  d["format_version"] = data.format_version;
  d["type"] = to_string(data.type);
  d["symmetry"] = to_string(data.symmetry);
  d["absolute_photometry"] = f.absolute_photometry;
  // Relative photometry: the lamp lumens flux_lm scales against; absolute: None.
  d["lamp_lumens_lm"] =
      f.absolute_photometry ? py::object(py::none()) : py::object(py::float_(f.rated_lumens_lm));
  d["rated_lumens_lm"] = f.rated_lumens_lm;
  d["lamp_count"] = f.lamp_count;
  d["integrated_lumens_lm"] = f.integrated_lumens_lm;
  d["peak_cd"] = f.peak_cd;
  d["peak_horizontal_deg"] = f.peak_horizontal_deg;
  d["peak_vertical_deg"] = f.peak_vertical_deg;
  d["beam_angle_deg"] = py::make_tuple(angle(f.beam_angle_deg[0]), angle(f.beam_angle_deg[1]));
  d["field_angle_deg"] = py::make_tuple(angle(f.field_angle_deg[0]), angle(f.field_angle_deg[1]));
  d["warnings"] = data.warnings;
  d["keywords"] = data.keywords;        // what the file says of itself: MANUFAC, LUMCAT, LAMP...
  d["input_watts"] = data.input_watts;  // IES input watts, LDT wattage (0 when not given)
  d["text"] = photometry_summary(data);
  return d;
}

}  // namespace

// A Python value as JSON, without going through text: NaN stays NaN, so the scene reader's
// own checks name the field ("expected a finite number") as they do for scene files.
nlohmann::json to_json(const py::handle& o, const std::string& where) {
  if (o.is_none()) return nullptr;
  if (py::isinstance<py::bool_>(o)) return o.cast<bool>();
  if (py::isinstance<py::int_>(o)) {
    // As the JSON parser stores them: non-negative integers unsigned (cells, photons).
    if (o.cast<py::int_>() >= py::int_(0)) return o.cast<std::uint64_t>();
    return o.cast<std::int64_t>();
  }
  if (py::isinstance<py::float_>(o)) return o.cast<double>();
  if (py::isinstance<py::str>(o)) return o.cast<std::string>();
  if (py::hasattr(o, "tolist")) return to_json(o.attr("tolist")(), where);  // numpy
  if (py::isinstance<py::dict>(o)) {
    nlohmann::json out = nlohmann::json::object();
    for (const auto& [key, value] : o.cast<py::dict>()) {
      out[py::str(key).cast<std::string>()] = to_json(value, where);
    }
    return out;
  }
  if (py::isinstance<py::sequence>(o)) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& item : o.cast<py::sequence>()) out.push_back(to_json(item, where));
    return out;
  }
  throw py::type_error(where + ": cannot use a " + std::string(py::str(o.get_type())) +
                       " as a scene value");
}

// Grid cells as numpy arrays of shape (nv, nu), added beside the results layout for scripts.
void add_cell_arrays(const TargetResult& t, py::dict d) {
  const std::vector<py::ssize_t> shape{t.nv, t.nu};
  py::array_t<double> lux(shape), lo(shape), hi(shape);
  py::array_t<std::uint64_t> hits(shape);
  for (std::size_t i = 0; i < t.cells.size(); ++i) {
    lux.mutable_data()[i] = t.cells[i].mean;
    lo.mutable_data()[i] = t.cells[i].ci_low;
    hi.mutable_data()[i] = t.cells[i].ci_high;
    hits.mutable_data()[i] = t.cells[i].hits;
  }
  d["cells_lux"] = lux;
  d["cells_ci_low_lux"] = lo;
  d["cells_ci_high_lux"] = hi;
  d["cells_hits"] = hits;
}

// One layout: the C++ serializer's text (what `lightsolver run --out` writes), read by Python's
// json module, so the two cannot drift; numpy cell arrays are added beside it, not instead.
py::dict results_dict(const Results& r) {
  py::dict d = py::module_::import("json").attr("loads")(results_to_json(r));
  py::list targets = d["targets"];
  for (std::size_t i = 0; i < r.targets.size(); ++i) {
    if (r.targets[i].is_grid) add_cell_arrays(r.targets[i], targets[i].cast<py::dict>());
  }
  return d;
}

ProgressFn python_progress(const py::object& progress, std::exception_ptr& error) {
  if (progress.is_none()) return {};
  // By reference: the callable outlives the run, and copying it would need the GIL.
  return [&progress, &error](std::uint64_t done, std::uint64_t total) {
    py::gil_scoped_acquire gil;
    try {
      py::object keep = progress(done, total);
      return keep.is_none() || keep.cast<bool>();
    } catch (...) {
      error = std::current_exception();  // re-raised once tracing has stopped
      return false;
    }
  };
}

namespace {

// A results dict as JSON text: the layout without the numpy cell arrays results_dict() adds
// beside it (rescale rebuilds them).
std::string results_text(const py::dict& results) {
  py::dict doc = results.attr("copy")();
  if (doc.contains("targets")) {
    py::list targets;
    for (const py::handle t : doc["targets"]) {
      py::dict target = t.attr("copy")();
      for (const char* key : {"cells_lux", "cells_ci_low_lux", "cells_ci_high_lux", "cells_hits"}) {
        if (target.contains(key)) PyDict_DelItemString(target.ptr(), key);
      }
      targets.append(target);
    }
    doc["targets"] = targets;
  }
  return py::str(py::module_::import("json").attr("dumps")(doc));
}

py::dict solve_py(const Scene& scene, const py::kwargs& keywords) {
  // Copied while the GIL is held: Python threads may change `scene` once tracing releases it.
  // solve() validates the copy (and reports dropped triangles among the warnings).
  const Scene snapshot = scene;
  SolveOptions opt;
  set_run_options(keywords, opt, every_keyword, {"progress", "cancel", "comm"}, "solve");
  const auto keyword = [&](const char* name) {
    return keywords.contains(name) ? py::object(keywords[name]) : py::object(py::none());
  };
  // An mpi4py communicator: every process calls solve() alike and gets the same results.
  if (const py::object comm = keyword("comm"); !comm.is_none()) {
    opt.processes = mpi::group_of_fortran_handle(comm.attr("py2f")().cast<std::int64_t>());
  }
  const py::object cancel = keyword("cancel");
  CancelToken token = cancel.is_none() ? CancelToken{} : cancel.cast<CancelToken>();
  opt.cancel = token.flag.get();
  std::exception_ptr callback_error;
  const py::object progress = keyword("progress");
  const ProgressFn fn = python_progress(progress, callback_error);
  Results r;
  {
    py::gil_scoped_release nogil;
    r = lightsolver::solve(snapshot, opt, fn);
  }
  if (callback_error) std::rethrow_exception(callback_error);
  return results_dict(r);
}

}  // namespace

PYBIND11_MODULE(lightsolver, m) {
  m.doc() = "Photon-tracing illuminance solver: lux with confidence intervals";
  m.attr("__version__") = version();
  m.attr("SCENE_FORMAT") = kSceneFormat;
  m.attr("RESULTS_FORMAT") = kResultsFormat;
  m.attr("OPTIMIZATION_FORMAT") = kOptimizationFormat;
  m.def("material_defaults", &material_defaults_dict,
        "{type: {key: value}}: what a material gets for each key a scene file leaves out");
  static py::exception<InputError> input_error(m, "InputError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      input_error(e.what());
    }
  });

  py::class_<CancelToken>(m, "CancelToken", "Cancels a running solve() from any thread")
      .def(py::init<>())
      .def("cancel", &CancelToken::cancel)
      .def_property_readonly("cancelled", &CancelToken::cancelled);

  bind_scene(m);  // lightsolver.Scene: a scene built in memory

  m.def(
      "backends",
      [] {
        py::list out;
        for (const BackendInfo& b : available_backends()) {
          py::dict d;
          d["name"] = b.name;
          d["description"] = b.description;
          d["gpu"] = b.gpu;
          d["available"] = b.available.value_or(false);
          out.append(d);
        }
        return out;
      },
      "The values solve(backend=...) accepts, \"auto\" first, then every backend built: dicts "
      "with name, description, gpu (traces through a GPU API) and available (a device it can "
      "start on exists here; finding out loads the GPU drivers)");
  m.def("load_scene", &load_scene, py::arg("path"), "Read and validate a scene file");
  m.def(
      "scene_from_json",
      [](const std::string& text, const std::string& base_dir) {
        return scene_from_json(text, "<string>", base_dir);
      },
      py::arg("text"), py::arg("base_dir") = ".", "Parse scene JSON text");
  m.def("solve", &solve_py, py::arg("scene"),
        ("solve(scene, **options): trace photons; returns the results dict (grid cells as "
         "numpy arrays (nv, nu)). Keywords (the run options, docs/scene-format.md \"Settings\"; "
         "a value out of range raises InputError naming it):" +
         keywords_doc(every_keyword) +
         "\n  progress=None: progress(done, total) may return False to stop; the result is then "
         "marked partial.\n  cancel=None: a CancelToken.\n  comm=None: an mpi4py communicator "
         "(e.g. MPI.COMM_WORLD under mpirun): every process calls solve() with the same "
         "arguments, each traces a slice of every batch and all get the results a single "
         "process would give, bit for bit (docs/cluster.md).\nThe dict's stop_reason says "
         "which limit ended the run: photons, accuracy, time, cancelled or decided.")
            .c_str());
  m.def("run_options", &run_options_list,
        "The run options table (lightsolver/run_options.hpp): one dict per option with name, "
        "type, default, help, min, max, min_open, max_open, range, scene_key, cli_flag, "
        "python_keyword, python_default, result_key, echoed_when, cost_and_study, per_backend");
  m.def("mpi_built", &mpi::built, "True when this build can share runs among MPI processes");
  m.def("mpi_launched", &mpi::launched,
        "True when an MPI launcher (mpirun, srun) started this process: its environment says so");
  m.def(
      "rescale",
      [](const py::dict& results, const std::map<std::string, double>& factors) {
        return results_dict(
            rescale_results(results_text(results), GroupFactors(factors.begin(), factors.end())));
      },
      py::arg("results"), py::arg("factors"),
      "Results of a run traced with contributions=True with each named luminaire group's flux "
      "multiplied by its factor ({'hall': 0.5}; 0 switches a group off): estimates, intervals, "
      "grid statistics and verdicts recomputed from the per-group tallies and direct parts "
      "(next-event estimation), no tracing; "
      "'rescaled' records the factors. ValueError (InputError) for an unknown group, a negative "
      "or non-finite factor, or results without contributions.");
  m.def(
      "check_scene", [](const Scene& s) { return check_dict(check_scene(s)); }, py::arg("scene"),
      "Check a Scene as a run would (validate, then the warnings a run gives before tracing) "
      "without changing it: {\"errors\": [...], \"warnings\": [...]}, each a dict with "
      "field (JSON path or ''), file, line (0 if none) and message. Errors hold the first error "
      "only (validation stops there).");
  m.def(
      "check_scene_file", [](const std::string& p) { return check_dict(check_scene_file(p)); },
      py::arg("path"), "check_scene for a scene file (a file that does not parse is one error)");
  m.def(
      "check_scene_json",
      [](const std::string& text, const std::string& base_dir) {
        return check_dict(check_scene_json(text, "<string>", base_dir));
      },
      py::arg("text"), py::arg("base_dir") = ".", "check_scene for scene JSON text");
  m.def(
      "write_polar_plot",
      [](const std::string& path, const std::string& png_path) {
        write_polar_plot_png(load_photometry(path), png_path);
      },
      py::arg("path"), py::arg("png_path"),
      "Writes the polar intensity diagram of an IES or LDT file (C0-C180 and C90-C270 planes) "
      "as a PNG, the same picture as `lightsolver photometry FILE --plot PNG`. Raises "
      "lightsolver.InputError for a bad file");
  m.def("photometry_summary", &photometry_summary_dict, py::arg("path"),
        "Facts of an IES or LDT file from the solver's parser: lamp_lumens_lm (None for absolute "
        "photometry), rated_lumens_lm, integrated_lumens_lm, peak_cd and its angles, "
        "beam_angle_deg and field_angle_deg (C0 and C90 planes; None where undefined), "
        "keywords ((key, value) pairs in file order: MANUFAC, LUMCAT, LAMP... or the EULUMDAT "
        "header fields), input_watts (0 if not given), warnings and the text summary. Raises "
        "lightsolver.InputError (a ValueError) for a bad "
        "file.");
  m.def(
      "ugr_table",
      [](const std::string& path, double spacing_to_height) {
        UgrTableOptions o;
        o.spacing_to_height = spacing_to_height;
        const UgrTable t = [&] {
          // Seconds of work without Python objects: other threads run meanwhile (the
          // workbench writes its report on a worker thread while the GUI stays responsive).
          py::gil_scoped_release nogil;
          return ugr_table(load_photometry(path), o);
        }();
        py::list refl, rows;
        for (const RoomReflectances& r : t.reflectances)
          refl.append(py::make_tuple(r.ceiling, r.walls, r.floor));
        for (const UgrTableRow& r : t.rows) {
          py::dict row;
          row["x_h"] = r.x_h;
          row["y_h"] = r.y_h;
          row["crosswise"] = r.crosswise;
          row["endwise"] = r.endwise;
          row["background_luminance_cd_m2"] = r.background_luminance_cd_m2;
          row["direct_floor_fraction"] = r.direct_floor_fraction;
          rows.append(row);
        }
        py::dict d;
        d["file"] = path;
        d["luminaire_flux_lm"] = t.luminaire_flux_lm;
        d["spacing_to_height"] = t.spacing_to_height;
        d["reflectances"] = refl;
        d["rows"] = rows;
        d["warnings"] = t.warnings;
        d["text"] = format_ugr_table(t);
        return d;
      },
      py::arg("path"), py::arg("spacing_to_height") = 0.25,
      "The luminaire's UGR table (CIE 190 tabular method; docs/glare.md), as `lightsolver "
      "photometry FILE --ugr-table` prints it: reflectances [(ceiling, walls, floor)], rows "
      "[{x_h, y_h, crosswise, endwise (one UGR per reflectance, None where no luminaire "
      "counts), background_luminance_cd_m2, direct_floor_fraction}], luminaire_flux_lm, "
      "warnings, text. Raises lightsolver.InputError for a bad file or one without a luminous "
      "area.");
  m.def(
      "cost",
      [](const Scene& scene, std::uint64_t max_photons, const py::kwargs& keywords) {
        const Scene snapshot = scene;  // copied with the GIL held, as in solve()
        CostOptions o;
        o.max_photons = max_photons;
        set_run_options(keywords, o.solve, checkpointed_keyword, {}, "cost");
        Cost c;
        {
          py::gil_scoped_release nogil;
          c = run_cost(snapshot, o);
        }
        py::list rows, goals;
        for (const Checkpoint& row : c.rows) {
          rows.append(
              py::dict(py::arg("photons") = row.photons, py::arg("seconds") = row.seconds,
                       py::arg("worst_relative_half_width") = row.worst_relative_half_width));
        }
        for (const CostGoal& g : c.goals) {
          goals.append(py::dict(py::arg("accuracy") = g.accuracy,
                                py::arg("photons") = g.need.photons,
                                py::arg("seconds") = g.need.seconds));
        }
        return py::dict(py::arg("rows") = rows, py::arg("goals") = goals,
                        py::arg("prepare_seconds") = c.prepare_seconds,
                        py::arg("results") = results_dict(c.results));
      },
      py::arg("scene"), py::arg("max_photons") = CostOptions{}.max_photons,
      ("What accuracy costs in time (`lightsolver cost`): ONE run of the largest checkpoint (1e4 "
       "photons, then 4x each, up to max_photons); rows: photons, tracing seconds and worst "
       "relative CI half-width at each checkpoint (infinity while a target has no hit); goals: "
       "photons and seconds per accuracy goal from the last row (width ~ 1/sqrt(N)); "
       "prepare_seconds: building the scene; results: the run's results dict (the same as "
       "solve() with the last row's photons). Keywords:" +
       keywords_doc(checkpointed_keyword))
          .c_str());
  m.def(
      "study",
      [](const Scene& scene, std::uint64_t max_photons, std::optional<std::string> reference,
         const py::kwargs& keywords) {
        const Scene snapshot = scene;  // copied with the GIL held, as in solve()
        StudyOptions o;
        o.max_photons = max_photons;
        o.reference_file = reference.value_or("");
        set_run_options(keywords, o.solve, checkpointed_keyword, {}, "study");
        Study st;
        {
          py::gil_scoped_release nogil;
          st = run_study(snapshot, o);
        }
        py::dict out = py::module_::import("json").attr("loads")(study_to_json(st));
        out["csv"] = study_to_csv(st);
        out["results"] = results_dict(st.results);
        return out;
      },
      py::arg("scene"), py::arg("max_photons") = StudyOptions{}.max_photons,
      py::arg("reference") = py::none(),
      ("What accuracy costs, shown (`lightsolver study`): ONE run with checkpoints at 1e4 photons, "
       "then 2x each, up to max_photons. Returns the study dict (lightsolver.study/1, "
       "docs/accuracy.md): rows (photons, seconds, 'all' and per-target Em, Emin, U0, per-cell "
       "mean and worst relative half-width and, with reference=RESULTS.json, mean and max "
       "relative error), fit, goals (photons and seconds per per-cell accuracy, 'extrapolated' "
       "beyond the last row), warnings; plus 'csv' (the CSV text) and 'results' (the run's). "
       "NativeSolver/python/tools/plot_study.py draws it. Keywords:" +
       keywords_doc(checkpointed_keyword))
          .c_str());
  bind_optimizer(m);   // lightsolver.optimize
  bind_simulation(m);  // lightsolver.Simulation
  bind_types(m);       // lightsolver.luminaire_types(), target_types()
  bind_provenance(m);  // lightsolver.verify_results
  bind_daylight(m);    // lightsolver.sun_position, read_weather
  bind_sky_patches(m);  // lightsolver.sky_patches, sky_vectors
  bind_annual(m);       // lightsolver.annual
  // lightsolver.direct_sun
  bind_direct_sun(m);
}
