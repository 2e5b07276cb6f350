// `lightsolver study`: accuracy against time at doubling photon counts, in one run, with the
// per-cell widths, Em/Emin/U0 and (against a reference) the actual error; then what each
// per-cell accuracy goal costs, from an N^-1/2 fit. docs/accuracy.md.
#include "lightsolver/study.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "io/json_reader.hpp"
#include "lightsolver/accuracy.hpp"
#include "lightsolver/defaults.hpp"
#include "lightsolver/simulation.hpp"
#include "types/target_types.hpp"

namespace lightsolver {
namespace {

using detail::JsonNode;
using Opt = std::optional<double>;

// Infinity (a width nothing can judge yet) is reported as "no value", never as inf.
Opt finite(double v) { return std::isfinite(v) ? Opt(v) : std::nullopt; }

std::string read_text(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file, "", "cannot read the reference results file");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

Estimate reference_estimate(const JsonNode& n, const char* mean_key) {
  Estimate e;
  e.mean = n.at(mean_key).number();
  e.ci_low = n.at("ci_low_lux").number();
  e.ci_high = n.at("ci_high_lux").number();
  if (!(e.ci_low <= e.mean && e.mean <= e.ci_high)) n.fail("interval does not hold its mean");
  return e;
}

// The reference's target `i`, checked against the scene's (same name, kind and cells).
TargetResult reference_target(const JsonNode& n, const Target& t, const std::string& scene_file) {
  const std::string from_other =
      " (the scene " + scene_file + " has \"" + t.name + "\"): the reference is from another scene";
  TargetResult r;
  r.name = n.at("name").string();
  if (r.name != t.name) n.at("name").fail("is \"" + r.name + "\"" + from_other);
  r.type = n.at("type").string();
  const detail::TargetType& row = detail::target_type(t.type);
  if (r.type != row.name) n.at("type").fail("is not the scene's target type" + from_other);
  r.is_grid = row.cells;
  r.estimate = reference_estimate(n, "mean_lux");
  if (!r.is_grid) return r;
  const JsonNode uv = n.at("cells_uv"), cells = n.at("cells");
  r.nu = static_cast<std::uint32_t>(uv[0].unsigned_integer());
  r.nv = static_cast<std::uint32_t>(uv[1].unsigned_integer());
  if (r.nu != t.nu || r.nv != t.nv || cells.array_size() != std::size_t(t.nu) * t.nv) {
    n.at("cells_uv")
        .fail("differs from the scene's " + std::to_string(t.nu) + " x " + std::to_string(t.nv) +
              " cells" + from_other);
  }
  for (std::size_t c = 0; c < cells.array_size(); ++c) {
    r.cells.push_back(reference_estimate(cells[c], "lux"));
  }
  return r;
}

// Per-cell widths and errors of one target against its reference (nullptr: none).
void add_cells(const TargetResult& t, const TargetResult* ref, StudyStats& s, double& error_sum,
               std::size_t& error_count) {
  const CellWidths w = cell_widths(t);
  s.mean_relative_half_width = finite(w.mean);
  s.worst_relative_half_width = finite(w.worst);
  if (!ref) return;
  double sum = 0.0, max = 0.0;
  std::size_t n = 0;
  const auto add_error = [&](double value, double reference) {
    if (const Opt e = cell_relative_error(value, reference, ref->estimate.mean)) {
      sum += *e;
      max = std::max(max, *e);
      ++n;
    }
  };
  if (t.is_grid) {
    for (std::size_t c = 0; c < t.cells.size(); ++c) add_error(t.cells[c].mean, ref->cells[c].mean);
  } else {
    add_error(t.estimate.mean, ref->estimate.mean);
  }
  if (ref->estimate.mean > 0.0) {
    s.em_relative_error = std::abs(t.estimate.mean - ref->estimate.mean) / ref->estimate.mean;
  }
  if (n == 0) return;
  s.mean_relative_error = sum / double(n);
  s.max_relative_error = max;
  error_sum += sum;
  error_count += n;
}

StudyRow make_row(const Checkpoint& c, const std::optional<StudyReference>& ref) {
  StudyRow row{c.photons, c.seconds, {}};
  StudyStats all;
  all.target = "*";
  const CellWidths w = cell_widths(c.targets);
  all.mean_relative_half_width = finite(w.mean);
  all.worst_relative_half_width = finite(w.worst);
  double error_sum = 0.0, error_max = 0.0;
  std::size_t error_count = 0;
  row.stats.push_back(all);
  for (std::size_t i = 0; i < c.targets.size(); ++i) {
    const TargetResult& t = c.targets[i];
    StudyStats s;
    s.target = t.name;
    s.em_lux = t.estimate.mean;
    s.em_ci_low_lux = t.estimate.ci_low;
    s.em_ci_high_lux = t.estimate.ci_high;
    if (t.is_grid) {
      s.emin_lux = t.min_lux;
      s.emax_lux = t.max_lux;
      s.u0 = t.uniformity;
    }
    add_cells(t, ref ? &ref->targets[i] : nullptr, s, error_sum, error_count);
    if (s.max_relative_error) error_max = std::max(error_max, *s.max_relative_error);
    row.stats.push_back(s);
  }
  if (error_count > 0) {
    row.stats[0].mean_relative_error = error_sum / double(error_count);
    row.stats[0].max_relative_error = error_max;
  }
  return row;
}

// Least-squares slope of log(y) against log(photons) over the rows where y is a positive value.
Opt log_log_slope(const std::vector<StudyRow>& rows, Opt StudyStats::*field) {
  std::vector<std::pair<double, double>> p;
  for (const StudyRow& r : rows) {
    const Opt y = r.stats[0].*field;
    if (y && *y > 0.0) p.emplace_back(std::log(double(r.photons)), std::log(*y));
  }
  if (p.size() < 2) return std::nullopt;
  double mx = 0.0, my = 0.0;
  for (const auto& [x, y] : p) mx += x / double(p.size()), my += y / double(p.size());
  double sxy = 0.0, sxx = 0.0;
  for (const auto& [x, y] : p) sxy += (x - mx) * (y - my), sxx += (x - mx) * (x - mx);
  return sxy / sxx;
}

// The N^-1/2 law fitted to the worst per-cell width of the last (at most 4) judged rows: the
// worst cell is the noisiest statistic, and the last rows are past the few-hit regime.
void fit_goals(Study& st) {
  constexpr std::size_t kFitRows = 4;
  double log_c = 0.0;
  for (auto r = st.rows.rbegin(); r != st.rows.rend() && st.fit.rows < kFitRows; ++r) {
    const Opt w = r->stats[0].worst_relative_half_width;
    if (!w || !(*w > 0.0)) break;
    log_c += std::log(*w) + 0.5 * std::log(double(r->photons));
    ++st.fit.rows;
  }
  if (st.fit.rows > 0) st.fit.coefficient = std::exp(log_c / double(st.fit.rows));
  st.fit.mean_width_exponent = log_log_slope(st.rows, &StudyStats::mean_relative_half_width);
  st.fit.worst_width_exponent = log_log_slope(st.rows, &StudyStats::worst_relative_half_width);
  st.fit.mean_error_exponent = log_log_slope(st.rows, &StudyStats::mean_relative_error);
  st.fit.max_error_exponent = log_log_slope(st.rows, &StudyStats::max_relative_error);
  for (const double goal : kCostGoals) {
    StudyGoal g;
    g.accuracy = goal;
    if (st.fit.coefficient && !st.rows.empty()) {
      const StudyRow& last = st.rows.back();
      const double photons = std::pow(*st.fit.coefficient / goal, 2);
      g.photons = photons;
      g.seconds = photons * last.seconds / double(last.photons);
      g.extrapolated = photons > double(last.photons);
    }
    st.goals.push_back(g);
  }
}

void check_reference_noise(Study& st) {
  if (!st.reference_mean_relative_half_width || st.rows.empty()) return;
  const Opt last = st.rows.back().stats[0].mean_relative_half_width;
  if (!last || *st.reference_mean_relative_half_width <= 0.25 * *last) return;
  char text[320];
  std::snprintf(text, sizeof text,
                "the reference's own cell intervals (mean ±%.3g %%) are not much narrower than "
                "the last row's (±%.3g %%): the errors of the last rows measure the reference's "
                "noise too; use a reference with at least 16x the photons",
                100.0 * *st.reference_mean_relative_half_width, 100.0 * *last);
  st.warnings.push_back(text);
}

nlohmann::json value(Opt v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); }

nlohmann::json stats_json(const StudyStats& s) {
  return {{"target", s.target},
          {"em_lux", value(s.em_lux)},
          {"em_ci_low_lux", value(s.em_ci_low_lux)},
          {"em_ci_high_lux", value(s.em_ci_high_lux)},
          {"emin_lux", value(s.emin_lux)},
          {"emax_lux", value(s.emax_lux)},
          {"u0", value(s.u0)},
          {"mean_relative_half_width", value(s.mean_relative_half_width)},
          {"worst_relative_half_width", value(s.worst_relative_half_width)},
          {"mean_relative_error", value(s.mean_relative_error)},
          {"max_relative_error", value(s.max_relative_error)},
          {"em_relative_error", value(s.em_relative_error)}};
}

std::string csv_field(Opt v) {
  if (!v) return "";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.10g", *v);
  return buf;
}

// A target name as one CSV field (RFC 4180: quoted when it holds a comma, quote or newline).
std::string csv_text(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (const char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

}  // namespace

std::vector<std::uint64_t> study_checkpoints(std::uint64_t max_photons) {
  std::vector<std::uint64_t> at;
  for (std::uint64_t n = 10'000; n <= max_photons; n *= 2) {
    at.push_back(n);
    if (n > max_photons / 2) break;  // the next step would pass max_photons (or overflow)
  }
  return at;
}

StudyReference load_study_reference(const std::string& file, const Scene& scene) {
  const nlohmann::json doc = detail::parse_json_text(read_text(file), file);
  const JsonNode root(doc, "", file);
  root.object();
  if (root.at("format").string() != kResultsFormat) {
    root.at("format").fail(std::string("is not \"") + kResultsFormat + "\": not a results file");
  }
  const std::string scene_name = scene.source_file.empty() ? "<scene>" : scene.source_file;
  const JsonNode targets = root.at("targets");
  if (targets.array_size() != scene.targets.size()) {
    targets.fail("has " + std::to_string(targets.array_size()) + " targets but the scene " +
                 scene_name + " has " + std::to_string(scene.targets.size()) +
                 ": the reference is from another scene");
  }
  const double flux = root.at("total_flux_lm").number(), scene_flux = scene.total_flux_lm();
  if (std::abs(flux - scene_flux) > 1e-9 * std::max(std::abs(flux), std::abs(scene_flux))) {
    char text[200];
    std::snprintf(text, sizeof text, "is %.9g lm but the scene's luminaires give %.9g lm", flux,
                  scene_flux);
    root.at("total_flux_lm").fail(std::string(text) + ": the reference is from another scene");
  }
  StudyReference ref{file, root.at("photons").unsigned_integer(), {}};
  for (std::size_t i = 0; i < scene.targets.size(); ++i) {
    ref.targets.push_back(reference_target(targets[i], scene.targets[i], scene_name));
  }
  return ref;
}

Study run_study(const Scene& scene, const StudyOptions& o,
                const std::function<void(const StudyRow&)>& on_row) {
  Study st;
  st.scene_file = scene.source_file;
  SolveOptions opt = o.solve;
  opt.checkpoints = study_checkpoints(o.max_photons);
  if (opt.checkpoints.empty()) throw InputError("", "max_photons", "must be >= 10000");
  if (!o.reference_file.empty()) {
    st.reference = load_study_reference(o.reference_file, scene);
    st.reference_mean_relative_half_width = finite(cell_widths(st.reference->targets).mean);
  }
  opt.photons = opt.checkpoints.back();
  opt.target_accuracy.reset();  // every checkpoint is reached
  opt.decide = false;           // even in a scene whose settings decide its requirements
  opt.checkpoint = [&](const Checkpoint& c) {
    st.rows.push_back(make_row(c, st.reference));
    if (on_row) on_row(st.rows.back());
  };
  const auto start = std::chrono::steady_clock::now();
  Simulation simulation(scene, {opt.backend, opt.threads, {}});
  st.prepare_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  st.results = simulation.run(opt);
  fit_goals(st);
  check_reference_noise(st);
  return st;
}

std::string study_to_json(const Study& st) {
  nlohmann::json rows = nlohmann::json::array();
  for (const StudyRow& r : st.rows) {
    nlohmann::json targets = nlohmann::json::array();
    for (std::size_t i = 1; i < r.stats.size(); ++i) targets.push_back(stats_json(r.stats[i]));
    rows.push_back({{"photons", r.photons},
                    {"seconds", r.seconds},
                    {"all", stats_json(r.stats[0])},
                    {"targets", std::move(targets)}});
  }
  nlohmann::json goals = nlohmann::json::array();
  for (const StudyGoal& g : st.goals) {
    goals.push_back({{"accuracy", g.accuracy},
                     {"photons", value(g.photons)},
                     {"seconds", value(g.seconds)},
                     {"extrapolated", g.extrapolated}});
  }
  nlohmann::json reference = nullptr;
  if (st.reference) {
    reference = {{"file", st.reference->file},
                 {"photons", st.reference->photons},
                 {"mean_relative_half_width", value(st.reference_mean_relative_half_width)}};
  }
  const Results& r = st.results;
  const nlohmann::json j = {{"format", "lightsolver.study/1"},
                            {"scene", st.scene_file},
                            {"backend", r.backend},
                            {"seed", r.seed},
                            {"confidence", r.confidence},
                            {"photons", r.photons},
                            {"partial", r.partial},
                            {"prepare_seconds", st.prepare_seconds},
                            {"dark_cell_fraction", kDarkCellFraction},
                            {"reference", reference},
                            {"rows", rows},
                            {"fit",
                             {{"rows", st.fit.rows},
                              {"coefficient", value(st.fit.coefficient)},
                              {"mean_width_exponent", value(st.fit.mean_width_exponent)},
                              {"worst_width_exponent", value(st.fit.worst_width_exponent)},
                              {"mean_error_exponent", value(st.fit.mean_error_exponent)},
                              {"max_error_exponent", value(st.fit.max_error_exponent)}}},
                            {"goals", goals},
                            {"warnings", st.warnings},
                            {"run_warnings", r.warnings}};
  return j.dump(2) + "\n";
}

std::string study_to_csv(const Study& st) {
  std::string out =
      "photons,seconds,target,em_lux,em_ci_low_lux,em_ci_high_lux,emin_lux,emax_lux,u0,"
      "mean_relative_half_width,worst_relative_half_width,mean_relative_error,"
      "max_relative_error,em_relative_error\n";
  for (const StudyRow& r : st.rows) {
    for (const StudyStats& s : r.stats) {
      out += std::to_string(r.photons) + "," + csv_field(r.seconds) + "," + csv_text(s.target);
      for (const Opt v : {s.em_lux, s.em_ci_low_lux, s.em_ci_high_lux, s.emin_lux, s.emax_lux, s.u0,
                          s.mean_relative_half_width, s.worst_relative_half_width,
                          s.mean_relative_error, s.max_relative_error, s.em_relative_error}) {
        out += ',';
        out += csv_field(v);
      }
      out += "\n";
    }
  }
  return out;
}

}  // namespace lightsolver
