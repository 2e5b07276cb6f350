// Results as JSON (lightsolver.results/1) and as a plain-text table for the terminal.
#include <nlohmann/json.hpp>

#include <cstdio>
#include <sstream>

#include "lightsolver/defaults.hpp"
#include "lightsolver/solver.hpp"

namespace lightsolver {
namespace {

nlohmann::json estimate_fields(const Estimate& e) {
  return {{"mean_lux", e.mean}, {"ci_low_lux", e.ci_low}, {"ci_high_lux", e.ci_high},
          {"sigma_lux", e.sigma}, {"hits", e.hits}};
}

nlohmann::json target_json(const TargetResult& t) {
  nlohmann::json j = {{"name", t.name}, {"type", t.is_grid ? "grid" : "surface"},
                      {"area_m2", t.area_m2}};
  j.update(estimate_fields(t.estimate));
  if (!t.is_grid) return j;
  j["cells_uv"] = {t.nu, t.nv};
  j["min_lux"] = t.min_lux;
  j["max_lux"] = t.max_lux;
  j["uniformity"] = t.uniformity;
  nlohmann::json cells = nlohmann::json::array();
  for (const auto& c : t.cells) {
    cells.push_back(
        {{"lux", c.mean}, {"ci_low_lux", c.ci_low}, {"ci_high_lux", c.ci_high}, {"hits", c.hits}});
  }
  j["cells"] = std::move(cells);
  return j;
}

std::string fmt(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

// Which limit ended the run, in words for the table's footer.
std::string stop_text(const Results& r) {
  if (r.stop_reason == kStopAccuracy) {
    return "stopped: accuracy goal " + fmt("±%g %%", 100.0 * r.target_accuracy.value_or(0.0)) +
           (r.accuracy_per_cell ? " per cell" : "") + " met";
  }
  if (r.stop_reason == kStopTime) {
    return "stopped: time limit " + fmt("%g s", r.max_seconds.value_or(0.0));
  }
  if (r.stop_reason == kStopCancelled) return "stopped: cancelled";
  return "stopped: photon count reached";
}

}  // namespace

std::string results_to_json(const Results& r) {
  nlohmann::json j = {{"format", kResultsFormat},
                      {"photons", r.photons},
                      {"photons_requested", r.photons_requested},
                      {"partial", r.partial},
                      {"stop_reason", r.stop_reason},
                      {"seconds", r.seconds},
                      {"backend", r.backend},
                      {"confidence", r.confidence},
                      {"seed", r.seed},
                      {"ray_segments", r.ray_segments},
                      {"capped_paths", r.capped_paths},
                      {"cut_paths", r.cut_paths},
                      {"total_flux_lm", r.total_flux_lm},
                      {"warnings", r.warnings}};
  if (r.max_seconds) j["max_seconds"] = *r.max_seconds;
  if (r.target_accuracy) {
    j["target_accuracy"] = *r.target_accuracy;
    j["accuracy_met"] = r.accuracy_met;
    j["accuracy_per_cell"] = r.accuracy_per_cell;
  }
  nlohmann::json targets = nlohmann::json::array();
  for (const auto& t : r.targets) targets.push_back(target_json(t));
  j["targets"] = std::move(targets);
  return j.dump(2) + "\n";
}

std::string results_table(const Results& r) {
  std::ostringstream out;
  char line[256];
  std::snprintf(line, sizeof line, "%-24s %12s %10s %10s %10s %10s %7s\n", "target", "E [lx]",
                "± [lx]", "hits", "Emin [lx]", "Emax [lx]", "U0");
  out << line;
  for (const auto& t : r.targets) {
    const Estimate& e = t.estimate;
    const double half = 0.5 * (e.ci_high - e.ci_low);
    std::snprintf(line, sizeof line, "%-24s %12s %10s %10llu", t.name.substr(0, 24).c_str(),
                  fmt("%.2f", e.mean).c_str(), fmt("%.2f", half).c_str(),
                  static_cast<unsigned long long>(e.hits));
    out << line;
    if (t.is_grid) {
      std::snprintf(line, sizeof line, " %10s %10s %7s", fmt("%.2f", t.min_lux).c_str(),
                    fmt("%.2f", t.max_lux).c_str(), fmt("%.3f", t.uniformity).c_str());
      out << line;
    }
    out << "\n";
  }
  std::snprintf(line, sizeof line,
                "%llu photons%s, %.0f%% confidence intervals, %s backend, %.2f s; %s\n",
                static_cast<unsigned long long>(r.photons), r.partial ? " (PARTIAL)" : "",
                100.0 * r.confidence, r.backend.c_str(), r.seconds, stop_text(r).c_str());
  out << line;
  for (const auto& w : r.warnings) out << "warning: " << w << "\n";
  return out.str();
}

}  // namespace lightsolver
