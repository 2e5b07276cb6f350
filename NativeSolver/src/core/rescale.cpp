// rescale: a results document with per-group tallies, re-read and rebuilt at other dimming
// factors by the code a traced run uses (target_results.cpp, decide.cpp, results_io.cpp).
#include "lightsolver/rescale.hpp"

#include <cmath>
#include <map>

#include "core/decide.hpp"
#include "core/json_reader.hpp"
#include "core/observer_grid_io.hpp"
#include "core/target_results.hpp"
#include "core/target_types.hpp"
#include "glare/glare_terms.hpp"
#include "lightsolver/defaults.hpp"
#include "lightsolver/error.hpp"

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

Requirements read_requirements(const JsonNode& n) {
  Requirements q;
  q.em_lux = optional_number(n, "em_lux");
  q.u0 = optional_number(n, "u0");
  q.emin_lux = optional_number(n, "emin_lux");
  q.ud = optional_number(n, "ud");
  q.ugr_max = optional_number(n, "ugr_max");
  if (n.has("task")) q.task = n.at("task").string();
  if (n.has("source")) q.source = n.at("source").string();
  return q;
}

// The factor of each group, in the results' group order; InputError for bad ones.
std::vector<double> group_factors(const JsonNode& groups, const GroupFactors& factors) {
  std::vector<double> out(groups.array_size(), 1.0);
  std::map<std::string, std::size_t> index;
  for (std::size_t g = 0; g < out.size(); ++g) index[groups[g].at("name").string()] = g;
  std::vector<bool> given(out.size(), false);
  for (const auto& [name, factor] : factors) {
    const auto it = index.find(name);
    if (it == index.end()) {
      std::string known;
      for (const auto& [n, _] : index) known += (known.empty() ? "\"" : ", \"") + n + "\"";
      throw InputError(
          groups.file(), "--dim " + name,
          "no luminaire group \"" + name + "\" in these results (groups: " + known + ")");
    }
    if (!(std::isfinite(factor) && factor >= 0.0)) {
      throw InputError(groups.file(), "--dim " + name,
                       "the factor must be a finite number >= 0 (0: off, 1: as traced)");
    }
    if (given[it->second]) {
      throw InputError(groups.file(), "--dim " + name, "the group is dimmed twice");
    }
    given[it->second] = true;
    out[it->second] = factor;
  }
  return out;
}

// A target of the results: what make_target needs (type, cells, requirements).
Target read_target(const JsonNode& n) {
  Target t;
  t.name = n.at("name").string();
  const std::string type = n.at("type").string();
  const detail::TargetType* row = detail::find_target_type(type);
  if (row == nullptr) n.at("type").fail("unknown target type \"" + type + "\"");
  t.type = row->type;
  if (row->cells) {
    t.nu = static_cast<std::uint32_t>(n.at("cells_uv")[0].unsigned_integer());
    t.nv = static_cast<std::uint32_t>(n.at("cells_uv")[1].unsigned_integer());
  }
  if (n.has("requirements")) t.requirements = read_requirements(n.at("requirements"));
  return t;
}

Tally read_tally(const JsonNode& n) {
  return {n.at("sum").unsigned_integer(), n.at("sum_sq").unsigned_integer()};
}

// An observer grid's per-point tallies ("points": [[sum, sum_sq], ...]) into each point's
// square (its cell bin is not read by the results); `group`: the group's tallies.
void read_point_tallies(const JsonNode& c, const detail::PreparedTarget& at, Tally* group) {
  const JsonNode list = c.at("points");
  if (list.array_size() != at.points) {
    list.fail("has " + std::to_string(list.array_size()) + " entries, expected one per point (" +
              std::to_string(at.points) + ")");
  }
  for (std::uint32_t k = 0; k < at.points; ++k) {
    const JsonNode p = list[k];
    if (p.array_size() != 2) p.fail("expected [sum, sum_sq]");
    group[at.point_bin(k)] = {p[0].unsigned_integer(), p[1].unsigned_integer()};
  }
}

// A plain observer's luminaires in the results as the glare terms of one eye (status, and
// L, omega, p of the counted ones), for the statistics step traced runs use (eye_glare).
GlareTerms observer_terms(const JsonNode& n) {
  GlareTerms terms;
  std::string status;
  std::vector<double> values;
  const JsonNode parts = n.at("luminaires");
  for (std::size_t i = 0; i < parts.array_size(); ++i) {
    const JsonNode p = parts[i];
    terms.luminaires.push_back(p.at("name").string());
    terms.not_rated.emplace_back();
    if (p.at("counted").boolean()) {
      status += 'c';
      for (const char* key : {"luminance_cd_m2", "solid_angle_sr", "position_index"}) {
        const double x = p.at(key).number();
        if (!(x > 0.0 && std::isfinite(x))) p.at(key).fail("must be > 0");
        values.push_back(x);
      }
      continue;
    }
    // A geometric reason has its status character; any other says why it is never rated.
    const std::string why = p.at("why_not").string();
    const char c = detail::geometric_status(why);
    if (c == 'x') terms.not_rated.back() = why;
    status += c;
  }
  terms.status.push_back(std::move(status));
  terms.terms.push_back(std::move(values));
  return terms;
}

// Each luminaire's dimming factor (its group's; 1 for a name no group lists), in `terms` order.
std::vector<double> luminaire_factors(const GlareTerms& terms,
                                      const std::map<std::string, double>& luminaire_factor) {
  std::vector<double> out;
  for (const std::string& name : terms.luminaires) {
    const auto f = luminaire_factor.find(name);
    out.push_back(f == luminaire_factor.end() ? 1.0 : f->second);
  }
  return out;
}

// The run's own fields, as traced.
void read_run(const JsonNode& root, Results& r) {
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
  r.warnings = strings(root.at("warnings"));
  r.max_seconds = optional_number(root, "max_seconds");
  r.target_accuracy = optional_number(root, "target_accuracy");
  if (r.target_accuracy) {
    r.accuracy_met = root.at("accuracy_met").boolean();
    r.accuracy_per_cell = root.at("accuracy_per_cell").boolean();
  }
  r.judged = root.has("verdict");
  if (r.judged) r.decide = root.at("decide").boolean();
}

}  // namespace

Results rescale_results(const std::string& results_json, const GroupFactors& factors,
                        const std::string& source) {
  const nlohmann::json doc = detail::parse_json_text(results_json, source);
  const JsonNode root(doc, "", source);
  if (root.at("format").string() != kResultsFormat) {
    root.at("format").fail(std::string("expected \"") + kResultsFormat + "\"");
  }
  if (!root.has("groups")) root.fail("results without luminaire groups: trace them again");
  const JsonNode groups = root.at("groups"), targets = root.at("targets");
  for (std::size_t i = 0; i < targets.array_size(); ++i) {
    if (!targets[i].has("contributions")) {
      targets[i].fail(
          "results without contributions: trace with --contributions (scene: "
          "settings.contributions) to rescale them");
    }
  }
  const std::vector<double> factor = group_factors(groups, factors);
  Results r;
  read_run(root, r);
  r.contributions = true;
  std::map<std::string, double> previous, luminaire_factor;
  if (root.has("rescaled")) {
    for (const auto& [name, f] : root.at("rescaled").object().items())
      previous[name] = f.get<double>();
  }
  detail::GroupedTallies tallies;
  std::vector<std::string> names;
  for (std::size_t g = 0; g < factor.size(); ++g) {
    const JsonNode n = groups[g];
    GroupResult gr;
    gr.name = n.at("name").string();
    gr.flux_lm = n.at("flux_lm").number() * factor[g];
    gr.photons = n.at("photons").unsigned_integer();
    for (std::size_t l = 0; l < n.at("luminaires").array_size(); ++l) {
      gr.luminaires.push_back(n.at("luminaires")[l].string());
      luminaire_factor[gr.luminaires.back()] = factor[g];
    }
    const auto p = previous.find(gr.name);
    r.rescaled.emplace_back(gr.name, factor[g] * (p == previous.end() ? 1.0 : p->second));
    r.total_flux_lm += gr.flux_lm;
    tallies.photons.push_back(gr.photons);
    tallies.flux_lm.push_back(gr.flux_lm);
    names.push_back(gr.name);
    r.groups.push_back(std::move(gr));
  }
  // Every target's bins end to end, laid out as prepare() lays them (append_target_bins).
  std::vector<Target> scene_targets;
  std::vector<detail::PreparedTarget> layout;
  std::vector<detail::BinInfo> bins;
  // Observer grids: their geometry, each luminance dimmed by its group's factor.
  std::map<std::size_t, detail::ObserverGridGeometry> eyes;
  for (std::size_t i = 0; i < targets.array_size(); ++i) {
    scene_targets.push_back(read_target(targets[i]));
    const Target& t = scene_targets.back();
    const detail::TargetType& row = detail::target_type(t.type);
    std::uint32_t points = row.eyes(t);
    if (t.type == Target::Type::ObserverGrid) {  // its eyes are read back with its geometry
      detail::ObserverGridGeometry g = detail::read_observer_grid_geometry(targets[i]);
      const std::vector<double> f = luminaire_factors(g.terms, luminaire_factor);
      g.terms = detail::dimmed(std::move(g.terms), f);
      points = static_cast<std::uint32_t>(g.terms.status.size());
      eyes[i] = std::move(g);
    }
    const double area = targets[i].at("area_m2").number();
    layout.push_back(detail::append_target_bins(bins, area, row.cells ? t.nu * t.nv : 0, points));
  }
  tallies.bin_count = bins.size();
  std::vector<Tally> counts(names.size() * bins.size());
  tallies.bins = &counts;
  for (std::size_t i = 0; i < targets.array_size(); ++i) {
    const JsonNode parts = targets[i].at("contributions");
    const detail::PreparedTarget& at = layout[i];
    for (std::size_t g = 0; g < names.size(); ++g) {
      const JsonNode c = parts.at(names[g].c_str());
      Tally* group = &counts[g * bins.size()];
      if (eyes.contains(i)) {
        read_point_tallies(c, at, group);
        continue;
      }
      group[at.bin] = read_tally(c);
      if (at.cells > 0 && c.at("cells").array_size() != at.cells) {
        c.at("cells").fail("wrong cell count");
      }
      for (std::uint32_t k = 0; k < at.cells; ++k)
        group[at.cell_bin(k)] = read_tally(c.at("cells")[k]);
    }
  }
  for (std::size_t i = 0; i < scene_targets.size(); ++i) {
    const auto grid = eyes.find(i);
    TargetResult t =
        detail::make_target(scene_targets[i], bins, tallies, layout[i], r.confidence, r.judged,
                            nullptr, grid == eyes.end() ? nullptr : &grid->second);
    if (t.is_observer && !t.observer_grid) {
      const GlareTerms terms = observer_terms(targets[i]);
      const GlareTerms dimmed = detail::dimmed(terms, luminaire_factors(terms, luminaire_factor));
      t.glare = detail::eye_glare(t.name, dimmed, 0, t.estimate);
    }
    detail::add_contributions(t, bins, tallies, layout[i], r.confidence, names);
    r.targets.push_back(std::move(t));
  }
  detail::add_verdicts(r);
  detail::add_to_decide(r, r.seconds > 0.0 ? double(r.photons) / r.seconds : 0.0);
  return r;
}

std::string rescale_results_json(const std::string& results_json, const GroupFactors& factors,
                                 const std::string& source) {
  return results_to_json(rescale_results(results_json, factors, source));
}

}  // namespace lightsolver
