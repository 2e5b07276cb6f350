// rescale: a results document with per-group tallies, read by results_from_json and rebuilt at
// other dimming factors by the code a traced run uses (target_results.cpp, decide.cpp,
// results_io.cpp).
#include "lightsolver/rescale.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "estimate/decide.hpp"
#include "results/results_glare.hpp"
#include "estimate/target_results.hpp"
#include "types/target_types.hpp"
#include "lightsolver/defaults.hpp"
#include "lightsolver/error.hpp"
#include "lightsolver/results_io.hpp"

namespace lightsolver {
namespace {

// Where an error in the results document is (InputError's field).
std::string at(std::size_t target, const std::string& rest = "") {
  return "targets[" + std::to_string(target) + "]" + (rest.empty() ? "" : "." + rest);
}

// The factor of each group, in the results' group order; InputError for bad ones.
std::vector<double> group_factors(const std::vector<GroupResult>& groups,
                                  const GroupFactors& factors, const std::string& source) {
  std::vector<double> out(groups.size(), 1.0);
  std::map<std::string, std::size_t> index;
  for (std::size_t g = 0; g < out.size(); ++g) index[groups[g].name] = g;
  std::vector<bool> given(out.size(), false);
  for (const auto& [name, factor] : factors) {
    const auto it = index.find(name);
    if (it == index.end()) {
      std::string known;
      for (const auto& [n, _] : index) known += (known.empty() ? "\"" : ", \"") + n + "\"";
      throw InputError(
          source, "--dim " + name,
          "no luminaire group \"" + name + "\" in these results (groups: " + known + ")");
    }
    if (!(std::isfinite(factor) && factor >= 0.0)) {
      throw InputError(source, "--dim " + name,
                       "the factor must be a finite number >= 0 (0: off, 1: as traced)");
    }
    if (given[it->second]) throw InputError(source, "--dim " + name, "the group is dimmed twice");
    given[it->second] = true;
    out[it->second] = factor;
  }
  return out;
}

// A target of the results: what make_target needs (type, cells, requirements).
Target scene_target(const TargetResult& in, std::size_t i, const std::string& source) {
  Target t;
  t.name = in.name;
  const detail::TargetType* row = detail::find_target_type(in.type);
  if (row == nullptr)
    throw InputError(source, at(i, "type"), "unknown target type \"" + in.type + "\"");
  t.type = row->type;
  if (row->cells) {
    t.nu = in.nu;
    t.nv = in.nv;
  }
  t.requirements = in.requirements;
  if (in.daylight_factor) t.quantity = Target::Quantity::DaylightFactor;
  return t;
}

// The sky of the results' daylight-factor grids (the first one's; every one reads the one
// sky): its group, its flux as traced (undimmed) and its outside illuminance. Empty without one.
std::optional<detail::DaylightFactorBasis> daylight_basis(const Results& in,
                                                          const std::vector<std::string>& groups,
                                                          const std::string& source) {
  for (std::size_t i = 0; i < in.targets.size(); ++i) {
    if (!in.targets[i].daylight_factor) continue;
    const DaylightFactorResult& d = *in.targets[i].daylight_factor;
    for (const LuminaireResult& l : in.luminaires) {
      if (l.name != d.sky) continue;
      const auto g = std::find(groups.begin(), groups.end(), l.group);
      if (g == groups.end()) break;
      return detail::DaylightFactorBasis{d.sky, std::size_t(g - groups.begin()),
                                         l.flux_lm * l.tilt_factor, d.outside_illuminance_lx};
    }
    throw InputError(source, at(i, "daylight_factor.sky"),
                     "no luminaire \"" + d.sky + "\" with a group in these results");
  }
  return std::nullopt;
}

// The run's own fields, as traced.
void copy_run(const Results& in, Results& r) {
  r.photons = in.photons;
  r.photons_requested = in.photons_requested;
  r.partial = in.partial;
  r.stop_reason = in.stop_reason;
  r.seconds = in.seconds;
  r.backend = in.backend;
  r.confidence = in.confidence;
  r.seed = in.seed;
  r.ray_segments = in.ray_segments;
  r.capped_paths = in.capped_paths;
  r.cut_paths = in.cut_paths;
  r.openings = in.openings;
  r.warnings = in.warnings;
  r.effects = in.effects;  // what the trace simulated (next-event estimation among them)
  r.max_seconds = in.max_seconds;
  r.target_accuracy = in.target_accuracy;
  r.accuracy_met = in.accuracy_met;
  r.accuracy_per_cell = in.accuracy_per_cell;
  r.judged = in.judged;
  r.decide = in.decide;
  r.provenance = in.provenance;  // the same trace of the same scene, other group fluxes
}

// Every luminaire as traced (absent from results older than the field), dimmed by its
// group's factor since the trace (`rescaled`, as recorded).
std::vector<LuminaireResult> dimmed_luminaires(const Results& in, const Results& r,
                                               const std::string& source) {
  std::map<std::string, double> factor(r.rescaled.begin(), r.rescaled.end());
  std::vector<LuminaireResult> out = in.luminaires;
  for (std::size_t i = 0; i < out.size(); ++i) {
    LuminaireResult& l = out[i];
    const auto f = factor.find(l.group);
    if (f == factor.end()) {
      throw InputError(source, "luminaires[" + std::to_string(i) + "].group",
                       "no luminaire group \"" + l.group + "\"");
    }
    l.dimming = f->second;
    l.emitted_flux_lm = l.flux_lm * l.tilt_factor * l.dimming;
  }
  return out;
}

// Target i's tallies of group part `c` into its bins (`layout`, as prepare() lays them) of the
// group's tallies `group`: the whole target, then its cells; an observer grid's (`points`) into
// each point's square (its cell bin is not read by the results).
void place_tallies(const Contribution& c, const detail::PreparedTarget& layout, bool points,
                   std::size_t i, const std::string& source, Tally* group) {
  const std::string where = at(i, "contributions." + c.group);
  if (points) {
    if (c.tallies.size() != layout.points) {
      throw InputError(source, where + ".points",
                       "has " + std::to_string(c.tallies.size()) +
                           " entries, expected one per point (" + std::to_string(layout.points) +
                           ")");
    }
    for (std::uint32_t k = 0; k < layout.points; ++k) group[layout.point_bin(k)] = c.tallies[k];
    return;
  }
  if (c.tallies.size() != 1 + std::size_t(layout.cells)) {
    throw InputError(source, where + ".cells", "wrong cell count");
  }
  group[layout.bin] = c.tallies[0];
  for (std::uint32_t k = 0; k < layout.cells; ++k) group[layout.cell_bin(k)] = c.tallies[1 + k];
}

// Next-event estimation, as the results recorded it in each group's contributions: which groups
// have direct parts, and whether photons deposit at all (the run's GroupedTallies fields).
// Results older than direct parts have none: every group's light is in its tallies.
void read_next_event(const Results& in, const std::string& source,
                     detail::GroupedTallies& tallies) {
  using Light = Contribution::PhotonLight;
  std::vector<Light> light(in.groups.size(), Light::All);
  for (std::size_t i = 0; i < in.targets.size(); ++i) {
    for (std::size_t g = 0; g < light.size(); ++g) {
      const Light l = in.targets[i].contributions[g].photon_light;
      if (i > 0 && l != light[g]) {
        throw InputError(source, at(i, "contributions." + in.groups[g].name + ".photon_light"),
                         "differs from the group's first target's (one run has one value)");
      }
      light[g] = l;
    }
  }
  tallies.next_event.assign(light.size(), 0);
  std::size_t reflected = 0, none = 0;
  for (std::size_t g = 0; g < light.size(); ++g) {
    tallies.next_event[g] = light[g] != Light::All;
    reflected += light[g] == Light::Reflected;
    none += light[g] == Light::None;
  }
  if (reflected > 0 && none > 0) {
    throw InputError(source, "targets[].contributions",
                     "photon_light \"reflected\" and \"none\" in one run (whether light "
                     "reflects is the scene's)");
  }
  tallies.photons_reflect = none == 0;
}

// Target i's direct parts of a next-event group (`c`) into its bins: the whole target, then its
// cells; none at an observer's or observer grid's eyes (they see reflected light only).
void place_direct(const Contribution& c, const detail::PreparedTarget& layout, bool eyes,
                  std::size_t i, const std::string& source, detail::DirectPart* group) {
  const std::string where = at(i, "contributions." + c.group + ".direct");
  if (eyes || layout.points > 0) {
    if (!c.direct.empty()) throw InputError(source, where, "an observer has no direct part");
    return;
  }
  if (c.direct.size() != 1 + std::size_t(layout.cells)) {
    throw InputError(source, where,
                     "missing: a group with photon_light needs the target's direct part and "
                     "each cell's");
  }
  const auto part = [](const DirectLight& d) {
    return detail::DirectPart{d.lux, d.variance_lx2, d.lit};
  };
  group[layout.bin] = part(c.direct[0]);
  for (std::uint32_t k = 0; k < layout.cells; ++k) {
    group[layout.cell_bin(k)] = part(c.direct[1 + k]);
  }
}

}  // namespace

Results rescale_results(const std::string& results_json, const GroupFactors& factors,
                        const std::string& source) {
  const Results in = results_from_json(results_json, source);
  if (in.groups.empty()) {
    throw InputError(source, "", "results without luminaire groups: trace them again");
  }
  for (std::size_t i = 0; i < in.targets.size(); ++i) {
    if (in.targets[i].contributions.empty()) {
      throw InputError(source, at(i),
                       "results without contributions: trace with --contributions (scene: "
                       "settings.contributions) to rescale them");
    }
  }
  const std::vector<double> factor = group_factors(in.groups, factors, source);
  Results r;
  copy_run(in, r);
  r.contributions = true;
  std::map<std::string, double> previous(in.rescaled.begin(), in.rescaled.end());
  detail::LuminaireFactors luminaire_factor;
  detail::GroupedTallies tallies;
  std::vector<std::string> names;
  for (std::size_t g = 0; g < factor.size(); ++g) {
    GroupResult gr = in.groups[g];
    gr.flux_lm *= factor[g];
    for (const std::string& l : gr.luminaires) luminaire_factor[l] = factor[g];
    const auto p = previous.find(gr.name);
    r.rescaled.emplace_back(gr.name, factor[g] * (p == previous.end() ? 1.0 : p->second));
    r.total_flux_lm += gr.flux_lm;
    tallies.photons.push_back(gr.photons);
    tallies.flux_lm.push_back(gr.flux_lm);
    names.push_back(gr.name);
    r.groups.push_back(std::move(gr));
  }
  r.luminaires = dimmed_luminaires(in, r, source);
  // Every target's bins end to end, laid out as prepare() lays them (append_target_bins).
  std::vector<Target> scene_targets;
  std::vector<detail::PreparedTarget> layout;
  std::vector<detail::BinInfo> bins;
  // Observer grids: their geometry, each luminance dimmed by its group's factor (glare's: it
  // sits above core, results_glare.hpp).
  const detail::ResultsGlare& glare = detail::results_glare();
  std::map<std::size_t, std::shared_ptr<const detail::ObserverGridGeometry>> eyes;
  for (std::size_t i = 0; i < in.targets.size(); ++i) {
    const TargetResult& t_in = in.targets[i];
    scene_targets.push_back(scene_target(t_in, i, source));
    const Target& t = scene_targets.back();
    const detail::TargetType& row = detail::target_type(t.type);
    std::uint32_t points = row.eyes(t);
    if (t.type == Target::Type::ObserverGrid) {  // its eyes are read back with its geometry
      const ObserverGridGlare& grid = t_in.observer_grid.value();
      if (grid.terms.status.empty()) {
        throw InputError(source, at(i, "observer_grid"),
                         "no glare_terms: trace with --contributions (scene: "
                         "settings.contributions)");
      }
      auto g = glare.observer_grid(grid, luminaire_factor);
      points = static_cast<std::uint32_t>(glare.points(*g));
      eyes[i] = std::move(g);
    }
    layout.push_back(
        detail::append_target_bins(bins, t_in.area_m2, row.cells ? t.nu * t.nv : 0, points));
  }
  tallies.bin_count = bins.size();
  std::vector<Tally> counts(names.size() * bins.size());
  tallies.bins = &counts;
  for (std::size_t i = 0; i < in.targets.size(); ++i) {
    for (std::size_t g = 0; g < names.size(); ++g) {
      place_tallies(in.targets[i].contributions[g], layout[i], eyes.contains(i), i, source,
                    &counts[g * bins.size()]);
    }
  }
  // Direct parts of next-event groups, at the fluxes the results report; dimmed as the photon
  // parts are (mean x f, variance x f^2: model/groups.cpp, group_estimate_z).
  read_next_event(in, source, tallies);
  std::vector<detail::DirectPart> direct;
  if (std::any_of(tallies.next_event.begin(), tallies.next_event.end(),
                  [](std::uint8_t n) { return n != 0; })) {
    direct.resize(names.size() * bins.size());
    tallies.direct = &direct;
    tallies.direct_scale = factor;
    for (std::size_t i = 0; i < in.targets.size(); ++i) {
      for (std::size_t g = 0; g < names.size(); ++g) {
        const Contribution& c = in.targets[i].contributions[g];
        if (tallies.next_event[g] != 0) {
          place_direct(c, layout[i], eyes.contains(i), i, source, &direct[g * bins.size()]);
        } else if (!c.direct.empty()) {
          throw InputError(source, at(i, "contributions." + c.group + ".direct"),
                           "a direct part needs photon_light \"reflected\" or \"none\"");
        }
      }
    }
  }
  const auto daylight = daylight_basis(in, names, source);
  for (std::size_t i = 0; i < scene_targets.size(); ++i) {
    const auto grid = eyes.find(i);
    TargetResult t = detail::make_target(scene_targets[i], bins, tallies, layout[i], r.confidence,
                                         /*grid_intervals=*/true, nullptr,
                                         grid == eyes.end() ? nullptr : grid->second.get(),
                                         daylight ? &*daylight : nullptr);
    if (t.is_observer && !t.observer_grid) {
      t.glare = glare.observer(in.targets[i].glare.value(), luminaire_factor, t.name, t.estimate,
                               source, at(i));
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
