// results_from_json: the results JSON (lightsolver.results/1) read back into Results, the
// inverse of results_to_json (results_io.cpp; groups_io.cpp and observer_grid_io.cpp read
// back what they write): every field written is read, so a round trip gives the same text.
#include <optional>
#include <string>
#include <vector>

#include "io/json_reader.hpp"
#include "lightsolver/defaults.hpp"
#include "lightsolver/results_io.hpp"
#include "results/daylight_factor_io.hpp"
#include "results/groups_io.hpp"
#include "results/observer_grid_io.hpp"
#include "scene/provenance.hpp"
#include "scene/sunlight_json.hpp"

namespace lightsolver {
namespace {

using detail::JsonNode;

std::optional<double> optional_number(const JsonNode& n, const char* key) {
  if (!n.has(key) || n.at(key).is_null()) return std::nullopt;
  return n.at(key).number();
}

std::vector<std::string> strings(const JsonNode& n) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < n.array_size(); ++i) out.push_back(n[i].string());
  return out;
}

std::vector<glm::dvec3> points(const JsonNode& n) {
  std::vector<glm::dvec3> out;
  for (std::size_t i = 0; i < n.array_size(); ++i) out.push_back(n[i].vec3());
  return out;
}

// {"mean_lux", "ci_low_lux", "ci_high_lux", "sigma_lux", "hits"}, or a cell's shorter
// spelling (`mean_key`, no sigma).
Estimate read_estimate(const JsonNode& n, const char* mean_key, bool sigma) {
  Estimate e;
  e.mean = n.at(mean_key).number();
  e.ci_low = n.at("ci_low_lux").number();
  e.ci_high = n.at("ci_high_lux").number();
  if (sigma) e.sigma = n.at("sigma_lux").number();
  e.hits = n.at("hits").unsigned_integer();
  return e;
}

VerdictKind verdict_kind(const JsonNode& n) {
  const std::string v = n.string();
  for (VerdictKind k : {VerdictKind::Pass, VerdictKind::Fail, VerdictKind::Undecided}) {
    if (v == to_string(k)) return k;
  }
  n.fail("expected \"pass\", \"fail\" or \"undecided\"");
}

Requirements read_requirements(const JsonNode& n) {
  Requirements q;
  q.em_lux = optional_number(n, "em_lux");
  q.u0 = optional_number(n, "u0");
  q.emin_lux = optional_number(n, "emin_lux");
  q.ud = optional_number(n, "ud");
  q.ugr_max = optional_number(n, "ugr_max");
  if (n.has("task")) q.task = n.at("task").string();
  if (n.has("source")) q.source = n.at("source").string();
  // A daylight-factor grid's: the percentages as they were in force, read back as given.
  q.df_target_percent = optional_number(n, "df_target_percent");
  q.df_minimum_percent = optional_number(n, "df_minimum_percent");
  q.median_diffuse_lx = optional_number(n, "median_diffuse_lx");
  if (n.has("en17037")) {
    const auto level = en17037_level(n.at("en17037").string());
    if (!level) n.at("en17037").fail("expected \"minimum\", \"medium\" or \"high\"");
    q.en17037 = *level;
  }
  return q;
}

Verdict read_verdict(const std::string& name, const JsonNode& n) {
  Verdict v;
  v.name = name;
  v.verdict = verdict_kind(n.at("verdict"));
  v.value_known = !n.at("value").is_null();
  if (v.value_known) v.value = n.at("value").number();
  v.ci_low = n.at("ci_low").number();
  v.ci_high_known = !n.at("ci_high").is_null();
  if (v.ci_high_known) v.ci_high = n.at("ci_high").number();
  v.required = n.at("required").number();
  const std::string relation = n.at("relation").string();
  if (relation != ">=" && relation != "<=") n.at("relation").fail("expected \">=\" or \"<=\"");
  v.relation = relation == ">=" ? ">=" : "<=";  // the static strings Verdict points to
  if (n.has("to_decide")) {
    const JsonNode d = n.at("to_decide");
    if (!d.at("photons").is_null())
      v.photons_to_decide = double(d.at("photons").unsigned_integer());
    v.seconds_to_decide = optional_number(d, "seconds");
  }
  return v;
}

// In the order the solver judges them (em, u0, emin, ud, ugr; a daylight-factor grid's
// df_target, df_minimum), not the JSON's key order.
std::vector<Verdict> read_verdicts(const JsonNode& n) {
  std::vector<Verdict> out;
  for (const char* name : {"df_target", "df_minimum", "em", "u0", "emin", "ud", "ugr"}) {
    if (n.has(name)) out.push_back(read_verdict(name, n.at(name)));
  }
  if (out.size() != n.object().size()) {
    n.fail("has a verdict other than em, u0, emin, ud, ugr, df_target, df_minimum");
  }
  return out;
}

GridIntervals read_grid_intervals(const JsonNode& n) {
  return {n.at("min_ci_low_lux").number(),
          n.at("min_ci_high_lux").number(),
          n.at("max_ci_low_lux").number(),
          n.at("max_ci_high_lux").number(),
          n.at("uniformity_ci_low").number(),
          n.at("uniformity_ci_high").number(),
          n.at("ud").number(),
          n.at("ud_ci_low").number(),
          n.at("ud_ci_high").number()};
}

// An observer's glare (add_glare): L_b with interval, UGR with interval, the luminaires' parts.
ObserverGlare read_glare(const JsonNode& n) {
  ObserverGlare g;
  g.background_luminance_cd_m2 = n.at("background_luminance_cd_m2").number();
  g.background_ci_low_cd_m2 = n.at("background_ci_low_cd_m2").number();
  g.background_ci_high_cd_m2 = n.at("background_ci_high_cd_m2").number();
  g.ugr = optional_number(n, "ugr");
  g.ugr_ci_low = optional_number(n, "ugr_ci_low");
  g.ugr_ci_high = optional_number(n, "ugr_ci_high");
  const JsonNode parts = n.at("luminaires");
  for (std::size_t i = 0; i < parts.array_size(); ++i) {
    const JsonNode p = parts[i];
    GlareContribution c;
    c.name = p.at("name").string();
    c.counted = p.at("counted").boolean();
    if (c.counted) {
      c.ugr_alone = optional_number(p, "ugr_alone");
      c.luminance_cd_m2 = p.at("luminance_cd_m2").number();
      c.solid_angle_sr = p.at("solid_angle_sr").number();
      c.position_index = p.at("position_index").number();
    } else {
      c.why_not = p.at("why_not").string();
    }
    g.contributions.push_back(std::move(c));
  }
  g.warnings = strings(n.at("warnings"));
  return g;
}

// An observer grid's points (observer_grid_json): per position one array over the directions.
ObserverGridGlare read_observer_grid(const JsonNode& target) {
  const JsonNode n = target.at("observer_grid");
  ObserverGridGlare g;
  g.positions = points(n.at("positions"));
  g.view_directions = points(n.at("view_directions"));
  const std::size_t nd = g.view_directions.size();
  g.points.resize(g.positions.size() * nd);
  const char* keys[] = {"background_luminance_cd_m2",
                        "background_ci_low_cd_m2",
                        "background_ci_high_cd_m2",
                        "ugr",
                        "ugr_ci_low",
                        "ugr_ci_high"};
  for (std::size_t k = 0; k < 6; ++k) {
    const JsonNode rows = n.at(keys[k]);
    if (rows.array_size() != g.positions.size()) rows.fail("expected one row per position");
    for (std::size_t p = 0; p < g.positions.size(); ++p) {
      if (rows[p].array_size() != nd) rows[p].fail("expected one value per view direction");
      for (std::size_t d = 0; d < nd; ++d) {
        const JsonNode v = rows[p][d];
        ObserverGlare& o = g.points[p * nd + d];
        const std::optional<double> x = v.is_null() ? std::nullopt : std::optional(v.number());
        if (k < 3 && !x) v.fail("expected a number");
        if (k == 0) o.background_luminance_cd_m2 = *x;
        if (k == 1) o.background_ci_low_cd_m2 = *x;
        if (k == 2) o.background_ci_high_cd_m2 = *x;
        if (k == 3) o.ugr = x;
        if (k == 4) o.ugr_ci_low = x;
        if (k == 5) o.ugr_ci_high = x;
      }
    }
  }
  if (!n.at("max_at").is_null()) {
    const JsonNode at = n.at("max_at");
    const std::uint64_t p = at.at("position").unsigned_integer();
    const std::uint64_t d = at.at("direction").unsigned_integer();
    if (p >= g.positions.size() || d >= nd) at.fail("names no point of the grid");
    g.max_at = p * nd + d;
  }
  if (n.has("glare_terms")) {
    g.terms = detail::read_glare_terms(n.at("glare_terms"), g.positions.size() * nd);
  }
  return g;
}

TargetResult read_target(const JsonNode& n, const std::vector<GroupResult>& groups) {
  TargetResult t;
  t.name = n.at("name").string();
  t.type = n.at("type").string();
  t.area_m2 = n.at("area_m2").number();
  t.estimate = read_estimate(n, "mean_lux", true);
  t.is_observer = n.has("background_luminance_cd_m2");
  if (t.is_observer) t.glare = read_glare(n);
  if (n.has("observer_grid")) t.observer_grid = read_observer_grid(n);
  t.is_grid = n.has("cells_uv");
  if (n.has("min_ci_low_lux")) t.intervals = read_grid_intervals(n);
  if (n.has("requirements")) {
    t.requirements = read_requirements(n.at("requirements"));
    t.verdicts = read_verdicts(n.at("verdicts"));
    t.verdict = verdict_kind(n.at("verdict"));
  }
  if (t.is_grid) {
    const JsonNode uv = n.at("cells_uv");
    if (uv.array_size() != 2) uv.fail("expected [nu, nv]");
    t.nu = static_cast<std::uint32_t>(uv[0].unsigned_integer());
    t.nv = static_cast<std::uint32_t>(uv[1].unsigned_integer());
    t.min_lux = n.at("min_lux").number();
    t.max_lux = n.at("max_lux").number();
    t.uniformity = n.at("uniformity").number();
    const JsonNode cells = n.at("cells");
    if (cells.array_size() != std::size_t(t.nu) * t.nv) cells.fail("expected nu x nv cells");
    for (std::size_t k = 0; k < cells.array_size(); ++k) {
      t.cells.push_back(read_estimate(cells[k], "lux", false));
    }
  }
  if (n.has("contributions")) t.contributions = detail::read_contributions_json(n, t, groups);
  if (n.has("daylight_factor")) {
    t.daylight_factor = detail::read_daylight_factor(n.at("daylight_factor"));
  }
  return t;
}

void read_effects(const JsonNode& root, Results& r) {
  if (!root.has("effects")) return;
  const JsonNode e = root.at("effects");
  r.effects.simulated = strings(e.at("simulated"));
  const JsonNode skipped = e.at("skipped");
  for (std::size_t i = 0; i < skipped.array_size(); ++i) {
    r.effects.skipped.push_back(
        {skipped[i].at("effect").string(), skipped[i].at("reason").string()});
  }
  if (!e.has("notes")) return;  // results written before notes, or with none
  const JsonNode notes = e.at("notes");
  for (std::size_t i = 0; i < notes.array_size(); ++i) {
    r.effects.notes.push_back({notes[i].at("effect").string(), notes[i].at("note").string()});
  }
}

}  // namespace

Results results_from_json(const std::string& text, const std::string& source) {
  const nlohmann::json doc = detail::parse_json_text(text, source);
  const JsonNode root(doc, "", source);
  if (root.at("format").string() == kOptimizationFormat) {
    root.at("format").fail(
        std::string("an optimizer's output (") + kOptimizationFormat +
        "), not results: it holds configurations, not their light; trace the chosen "
        "configuration's scene for its results (docs/optimization.md, \"Provenance and "
        "configurations\"), or `lightsolver verify SCENE` it against its scene");
  }
  if (root.at("format").string() != kResultsFormat) {
    root.at("format").fail(std::string("expected \"") + kResultsFormat + "\"");
  }
  Results r;
  r.photons = root.at("photons").unsigned_integer();
  r.photons_requested = root.at("photons_requested").unsigned_integer();
  r.partial = root.at("partial").boolean();
  r.stop_reason = root.at("stop_reason").string();
  r.seconds = root.at("seconds").number();
  r.backend = root.at("backend").string();
  r.confidence = root.at("confidence").number();
  r.seed = root.at("seed").unsigned_integer();
  r.ray_segments = root.at("ray_segments").unsigned_integer();
  r.capped_paths = root.at("capped_paths").unsigned_integer();
  r.cut_paths = root.at("cut_paths").unsigned_integer();
  r.total_flux_lm = root.at("total_flux_lm").number();
  r.warnings = strings(root.at("warnings"));
  r.max_seconds = optional_number(root, "max_seconds");
  r.target_accuracy = optional_number(root, "target_accuracy");
  if (r.target_accuracy) {
    r.accuracy_met = root.at("accuracy_met").boolean();
    r.accuracy_per_cell = root.at("accuracy_per_cell").boolean();
  }
  r.judged = root.has("verdict");
  if (r.judged) {
    r.verdict = verdict_kind(root.at("verdict"));
    r.decide = root.at("decide").boolean();
  }
  read_effects(root, r);
  detail::read_groups_json(root, r);
  // Results written before provenance was recorded have none (null is not written).
  if (root.has("provenance")) r.provenance = detail::read_provenance(root.at("provenance"));
  if (root.has("sunlight_exposure"))
    r.sunlight_exposure = detail::read_sunlight_exposure_result(root.at("sunlight_exposure"));
  const JsonNode targets = root.at("targets");
  for (std::size_t i = 0; i < targets.array_size(); ++i) {
    r.targets.push_back(read_target(targets[i], r.groups));
    r.contributions = r.contributions || !r.targets.back().contributions.empty();
  }
  return r;
}

}  // namespace lightsolver
