// Results as JSON (lightsolver.results/1) and as a plain-text table for the terminal.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>

#include "results/daylight_factor_io.hpp"
#include "results/effects_io.hpp"
#include "results/groups_io.hpp"
#include "results/observer_grid_io.hpp"
#include "scene/provenance.hpp"
#include "lightsolver/defaults.hpp"
#include "lightsolver/run_options.hpp"
#include "lightsolver/solver.hpp"

namespace lightsolver {
namespace {

nlohmann::json estimate_fields(const Estimate& e) {
  return {{"mean_lux", e.mean},
          {"ci_low_lux", e.ci_low},
          {"ci_high_lux", e.ci_high},
          {"sigma_lux", e.sigma},
          {"hits", e.hits}};
}

// The requirements as resolved (table row values with the scene's own on top).
nlohmann::json requirements_json(const Requirements& q) {
  nlohmann::json j = nlohmann::json::object();
  if (q.em_lux) j["em_lux"] = *q.em_lux;
  if (q.u0) j["u0"] = *q.u0;
  if (q.emin_lux) j["emin_lux"] = *q.emin_lux;
  if (q.ud) j["ud"] = *q.ud;
  if (q.ugr_max) j["ugr_max"] = *q.ugr_max;
  if (q.en17037 != En17037Level::None) j["en17037"] = to_string(q.en17037);
  if (q.median_diffuse_lx) j["median_diffuse_lx"] = *q.median_diffuse_lx;
  if (const auto d = q.df_target()) j["df_target_percent"] = *d;  // as in force
  if (const auto d = q.df_minimum()) j["df_minimum_percent"] = *d;
  if (!q.task.empty()) j["task"] = q.task;
  if (!q.source.empty()) j["source"] = q.source;
  return j;
}

nlohmann::json optional_number(const std::optional<double>& v) {
  return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
}

nlohmann::json verdicts_json(const std::vector<Verdict>& verdicts) {
  nlohmann::json j = nlohmann::json::object();
  for (const Verdict& v : verdicts) {
    nlohmann::json one = {{"verdict", to_string(v.verdict)},
                          {"value", v.value_known ? nlohmann::json(v.value) : nullptr},
                          {"ci_low", v.ci_low},
                          {"ci_high", v.ci_high_known ? nlohmann::json(v.ci_high) : nullptr},
                          {"required", v.required},
                          {"relation", v.relation}};
    if (v.verdict == VerdictKind::Undecided) {
      const auto photons = v.photons_to_decide;  // a whole count (estimates are finite)
      one["to_decide"] = {
          {"photons",
           photons ? nlohmann::json(static_cast<std::uint64_t>(std::ceil(std::min(*photons, 1e19))))
                   : nlohmann::json(nullptr)},
          {"seconds", optional_number(v.seconds_to_decide)}};
    }
    j[v.name] = std::move(one);
  }
  return j;
}

void add_grid_intervals(const GridIntervals& g, nlohmann::json& j) {
  j["min_ci_low_lux"] = g.min_low;
  j["min_ci_high_lux"] = g.min_high;
  j["max_ci_low_lux"] = g.max_low;
  j["max_ci_high_lux"] = g.max_high;
  j["uniformity_ci_low"] = g.u0_low;
  j["uniformity_ci_high"] = g.u0_high;
  j["ud"] = g.ud;
  j["ud_ci_low"] = g.ud_low;
  j["ud_ci_high"] = g.ud_high;
}

// Requirements, verdicts and overall verdict: only on targets with requirements, so results
// of scenes without any keep their layout (and the golden files their bits).
void add_compliance(const TargetResult& t, nlohmann::json& j) {
  if (t.intervals) add_grid_intervals(*t.intervals, j);
  if (!t.requirements.any()) return;
  j["requirements"] = requirements_json(t.requirements);
  j["verdicts"] = verdicts_json(t.verdicts);
  j["verdict"] = to_string(t.verdict);
}

// An observer's glare: L_b and its interval, UGR and its interval (null where unbounded or
// absent: no luminaire counts), each luminaire's part, and the remarks.
void add_glare(const ObserverGlare& g, nlohmann::json& j) {
  j["background_luminance_cd_m2"] = g.background_luminance_cd_m2;
  j["background_ci_low_cd_m2"] = g.background_ci_low_cd_m2;
  j["background_ci_high_cd_m2"] = g.background_ci_high_cd_m2;
  j["ugr"] = optional_number(g.ugr);
  j["ugr_ci_low"] = optional_number(g.ugr_ci_low);
  j["ugr_ci_high"] = optional_number(g.ugr_ci_high);
  nlohmann::json parts = nlohmann::json::array();
  for (const GlareContribution& c : g.contributions) {
    nlohmann::json one = {{"name", c.name}, {"counted", c.counted}};
    if (c.counted) {
      one["ugr_alone"] = optional_number(c.ugr_alone);
      one["luminance_cd_m2"] = c.luminance_cd_m2;
      one["solid_angle_sr"] = c.solid_angle_sr;
      one["position_index"] = c.position_index;
    } else {
      one["why_not"] = c.why_not;
    }
    parts.push_back(std::move(one));
  }
  j["luminaires"] = std::move(parts);
  j["warnings"] = g.warnings;
}

// An observer grid's points: positions and view directions, then per position one array over
// the directions of L_b, UGR and the UGR interval (null where unbounded or without glare).
nlohmann::json observer_grid_json(const ObserverGridGlare& g) {
  const auto points = [](const std::vector<glm::dvec3>& v) {
    nlohmann::json a = nlohmann::json::array();
    for (const auto& p : v) a.push_back({p.x, p.y, p.z});
    return a;
  };
  nlohmann::json j = {{"positions", points(g.positions)},
                      {"view_directions", points(g.view_directions)}};
  const std::size_t nd = g.view_directions.size();
  nlohmann::json lb = nlohmann::json::array(), lb_low = lb, lb_high = lb, ugr = lb, ugr_low = lb,
                 ugr_high = lb;
  for (std::size_t p = 0; p < g.positions.size(); ++p) {
    nlohmann::json rows[6];
    for (auto& r : rows) r = nlohmann::json::array();
    for (std::size_t d = 0; d < nd; ++d) {
      const ObserverGlare& o = g.points[p * nd + d];
      rows[0].push_back(o.background_luminance_cd_m2);
      rows[1].push_back(o.background_ci_low_cd_m2);
      rows[2].push_back(o.background_ci_high_cd_m2);
      rows[3].push_back(optional_number(o.ugr));
      rows[4].push_back(optional_number(o.ugr_ci_low));
      rows[5].push_back(optional_number(o.ugr_ci_high));
    }
    lb.push_back(rows[0]);
    lb_low.push_back(rows[1]);
    lb_high.push_back(rows[2]);
    ugr.push_back(rows[3]);
    ugr_low.push_back(rows[4]);
    ugr_high.push_back(rows[5]);
  }
  j["background_luminance_cd_m2"] = std::move(lb);
  j["background_ci_low_cd_m2"] = std::move(lb_low);
  j["background_ci_high_cd_m2"] = std::move(lb_high);
  j["ugr"] = std::move(ugr);
  j["ugr_ci_low"] = std::move(ugr_low);
  j["ugr_ci_high"] = std::move(ugr_high);
  j["max_at"] = nullptr;
  if (g.max_at) j["max_at"] = {{"position", *g.max_at / nd}, {"direction", *g.max_at % nd}};
  return j;
}

nlohmann::json target_json(const TargetResult& t) {
  nlohmann::json j = {{"name", t.name}, {"type", t.type}, {"area_m2", t.area_m2}};
  j.update(estimate_fields(t.estimate));
  if (t.glare) add_glare(*t.glare, j);
  if (t.observer_grid) {
    j["observer_grid"] = observer_grid_json(*t.observer_grid);
    // What a rescale rebuilds the points from: only with the tallies it needs too.
    if (!t.contributions.empty()) {
      j["observer_grid"]["glare_terms"] = detail::glare_terms_json(t.observer_grid->terms);
    }
  }
  add_compliance(t, j);
  detail::add_contributions_json(t, j);
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
  if (t.daylight_factor) j["daylight_factor"] = detail::daylight_factor_json(*t.daylight_factor);
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
  if (r.stop_reason == kStopDecided) return "stopped: every verdict decided";
  return "stopped: photon count reached";
}

}  // namespace

std::string results_to_json(const Results& r) {
  // The options a run echoes take their keys from the run options table.
  nlohmann::json j = {{"format", kResultsFormat},
                      {"photons", r.photons},
                      {result_key("photons"), r.photons_requested},
                      {"partial", r.partial},
                      {"stop_reason", r.stop_reason},
                      {"seconds", r.seconds},
                      {result_key("backend"), r.backend},
                      {result_key("confidence"), r.confidence},
                      {result_key("seed"), r.seed},
                      {"ray_segments", r.ray_segments},
                      {"capped_paths", r.capped_paths},
                      {"cut_paths", r.cut_paths},
                      {"total_flux_lm", r.total_flux_lm},
                      {"warnings", r.warnings}};
  if (r.max_seconds) j[result_key("max_seconds")] = *r.max_seconds;
  j["effects"] = detail::effects_json(r.effects);
  if (r.target_accuracy) {
    j[result_key("target_accuracy")] = *r.target_accuracy;
    j["accuracy_met"] = r.accuracy_met;
    j[result_key("accuracy_per_cell")] = r.accuracy_per_cell;
  }
  if (r.judged) {
    j["verdict"] = to_string(r.verdict);
    j[result_key("decide")] = r.decide;
  }
  nlohmann::json targets = nlohmann::json::array();
  for (const auto& t : r.targets) targets.push_back(target_json(t));
  j["targets"] = std::move(targets);
  detail::add_groups_json(r, j);
  if (r.provenance) j["provenance"] = detail::provenance_json(*r.provenance);
  if (r.sunlight_exposure) j["sunlight_exposure"] = sunlight_exposure_json(*r.sunlight_exposure);
  return j.dump(2) + "\n";
}

namespace {

// One line per requirement: "  desk: u0 0.612 [0.571, 0.655] >= 0.6: undecided (to decide:
// about 4.1e+06 photons, 12 s)".
void verdict_lines(const Results& r, std::ostringstream& out) {
  for (const auto& t : r.targets) {
    for (const Verdict& v : t.verdicts) {
      const char* f = v.name == "u0" || v.name == "ud" ? "%.3f" : "%.2f";
      out << "  " << t.name << ": " << v.name << " " << (v.value_known ? fmt(f, v.value) : "-")
          << " [" << fmt(f, v.ci_low) << ", " << (v.ci_high_known ? fmt(f, v.ci_high) : "open")
          << "] " << v.relation << " " << fmt("%g", v.required) << ": " << to_string(v.verdict);
      if (v.verdict == VerdictKind::Undecided) {
        out << " (to decide: "
            << (v.photons_to_decide ? "about " + fmt("%.2g", *v.photons_to_decide) + " photons"
                                    : std::string("unknown"))
            << (v.seconds_to_decide ? ", " + fmt("%.2g", *v.seconds_to_decide) + " s" : "") << ")";
      }
      out << "\n";
    }
  }
}

// Where an observer grid's maximum is ("" for an observer).
std::string max_place(const TargetResult& t) {
  if (!t.observer_grid || !t.observer_grid->max_at) return "";
  const ObserverGridGlare& g = *t.observer_grid;
  const std::size_t k = *g.max_at, nd = g.view_directions.size();
  const glm::dvec3 p = g.positions[k / nd], v = g.view_directions[k % nd];
  char at[160];
  std::snprintf(at, sizeof at, " at (%.3g, %.3g, %.3g) looking (%.2f, %.2f, %.2f)", p.x, p.y, p.z,
                v.x, v.y, v.z);
  return at;
}

}  // namespace

std::string results_table(const Results& r, bool list_skipped_effects) {
  std::ostringstream out;
  char line[256];
  std::snprintf(line, sizeof line, "%-24s %12s %10s %10s %10s %10s %7s", "target", "E [lx]",
                "± [lx]", "hits", "Emin [lx]", "Emax [lx]", "U0");
  out << line << (r.judged ? " verdict\n" : "\n");
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
    } else if (t.requirements.any()) {  // pad to the verdict column
      std::snprintf(line, sizeof line, " %10s %10s %7s", "", "", "");
      out << line;
    }
    if (t.requirements.any())
      out << " " << (t.verdict == VerdictKind::Fail ? "FAIL" : to_string(t.verdict));
    out << "\n";
  }
  std::snprintf(line, sizeof line,
                "%llu photons%s, %.0f%% confidence intervals, %s backend, %.2f s; %s\n",
                static_cast<unsigned long long>(r.photons), r.partial ? " (PARTIAL)" : "",
                100.0 * r.confidence, r.backend.c_str(), r.seconds, stop_text(r).c_str());
  out << line;
  for (const auto& t : r.targets) {
    if (!t.glare) continue;
    const ObserverGlare& g = *t.glare;
    const auto show = [](const std::optional<double>& v) { return v ? fmt("%.1f", *v) : "-"; };
    out << (t.observer_grid ? "observer grid " : "observer ") << t.name
        << (t.observer_grid ? ": max UGR " : ": UGR ") << show(g.ugr) << " [" << show(g.ugr_ci_low)
        << ", " << show(g.ugr_ci_high) << "], L_b " << fmt("%.3g", g.background_luminance_cd_m2)
        << " cd/m2 [" << fmt("%.3g", g.background_ci_low_cd_m2) << ", "
        << fmt("%.3g", g.background_ci_high_cd_m2) << "]" << max_place(t) << "\n";
    for (const auto& w : g.warnings) out << "warning: " << w << "\n";
  }
  for (const auto& t : r.targets) {
    if (t.daylight_factor) out << detail::daylight_factor_line(t.name, *t.daylight_factor);
  }
  if (r.judged) {
    out << "verdicts (" << (r.decide ? "traced until decided" : "at the photons traced")
        << "): " << to_string(r.verdict) << "\n";
    verdict_lines(r, out);
  }
  if (r.sunlight_exposure) out << sunlight_exposure_table(*r.sunlight_exposure);
  out << detail::effects_lines(r.effects, list_skipped_effects);
  for (const auto& w : r.warnings) out << "warning: " << w << "\n";
  return out.str();
}

}  // namespace lightsolver
