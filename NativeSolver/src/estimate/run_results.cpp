#include "estimate/run_results.hpp"

#include <cstdio>
#include <string>

#include "estimate/daylight_factor.hpp"
#include "estimate/target_results.hpp"
#include "types/luminaire_types.hpp"

namespace lightsolver::detail {

std::vector<TargetResult> all_targets(const Scene& scene, const PreparedScene& s,
                                      const GroupedTallies& tallies, double confidence, bool judged,
                                      bool contributions,
                                      const std::vector<Luminaire>* luminaires) {
  std::vector<std::string> names;
  for (const auto& g : s.groups) names.push_back(g.name);
  const std::optional<DaylightFactorBasis> daylight = daylight_factor_basis(scene, s.groups);
  std::vector<TargetResult> out;
  for (std::size_t i = 0; i < scene.targets.size(); ++i) {
    const Target& target = scene.targets[i];
    const PreparedTarget& at = s.targets[i];
    TargetResult r = make_target(target, s.bins, tallies, at, confidence, judged,
                                 luminaires != nullptr ? luminaires : &scene.luminaires, nullptr,
                                 daylight ? &*daylight : nullptr);
    if (contributions) add_contributions(r, s.bins, tallies, at, confidence, names);
    out.push_back(std::move(r));
  }
  return out;
}

std::vector<TargetResult> all_targets(const Scene& scene, const PreparedScene& s,
                                      const TallyBlock& t, std::uint64_t photons, double confidence,
                                      bool judged, bool contributions) {
  return all_targets(scene, s, grouped_tallies(s, t.bins, photons), confidence, judged,
                     contributions);
}

std::vector<GroupResult> group_results(const Scene& scene, const PreparedScene& s,
                                       const std::vector<std::uint64_t>& photons) {
  std::vector<GroupResult> out;
  for (const PreparedGroup& g : s.groups) {
    GroupResult r{g.name, g.flux_lm, photons[out.size()], {}};
    for (const std::uint32_t l : g.luminaires) r.luminaires.push_back(scene.luminaires[l].name);
    out.push_back(std::move(r));
  }
  return out;
}

std::vector<LuminaireResult> luminaire_results(const Scene& scene, const PreparedScene& s,
                                               const std::vector<double>& dimming) {
  std::vector<LuminaireResult> out(scene.luminaires.size());
  for (std::size_t g = 0; g < s.groups.size(); ++g) {
    const double factor = g < dimming.size() ? dimming[g] : 1.0;
    for (const std::uint32_t i : s.groups[g].luminaires) {
      const Luminaire& l = scene.luminaires[i];
      LuminaireResult& r = out[i];
      r = {l.name,    luminaire_type(l.type).name, s.groups[g].name,
           l.flux_lm, photometric_tilt_factor(l),  factor,
           0.0};
      // The flux prepare() traced for it (its row's emitted_flux, TILT applied) and added into
      // the group's flux, dimmed.
      r.emitted_flux_lm = s.luminaires[i].flux_lm * r.dimming;
    }
  }
  return out;
}

namespace {

// The share of daylight photons blocked outside their openings (docs/daylight.md, "Portals").
void add_opening_warnings(Results& r) {
  const OpeningCounts& o = r.openings;
  if (o.blocked == 0 || o.photons == 0) return;
  auto percent = [&](std::uint64_t n) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g %%", 100.0 * double(n) / double(o.photons));
    return std::string(text);
  };
  r.warnings.push_back(
      percent(o.blocked) + " of the daylight photons entering through portals or a sun's " +
      "opening (" + std::to_string(o.blocked) + " of " + std::to_string(o.photons) +
      ") were blocked by the scene outside their opening: exterior obstructions cast their " +
      "shadow but reflect nothing through a portal (a sky without portals also traces their " +
      "reflections)");
  if (o.glass > 0) {
    r.warnings.push_back(
        percent(o.glass) + " of the daylight photons through openings met a modelled glass " +
        "surface outside their opening and were blocked: a portal's or sun opening's glazing " +
        "replaces a modelled pane; leave the pane out or put the opening outside it");
  }
}

}  // namespace

void add_warnings(const Scene& scene, Results& r) {
  r.warnings = scene.warnings;
  for (const Luminaire& l : scene.luminaires) {
    const Warnings w = photometric_warnings(l);
    r.warnings.insert(r.warnings.end(), w.begin(), w.end());
  }
  if (r.total_flux_lm <= 0.0) r.warnings.push_back("all luminaires have zero flux");
  if (r.capped_paths > 0) {
    r.warnings.push_back(std::to_string(r.capped_paths) +
                         " photon path(s) were still alive at max_bounces = " +
                         std::to_string(scene.settings.max_bounces) +
                         "; their remaining light is lost, so results are biased low");
  }
  if (r.cut_paths > 0) {
    r.warnings.push_back(std::to_string(r.cut_paths) + " photon path(s) on the " + r.backend +
                         " backend were longer than its device can run (Mesa lavapipe stops a "
                         "shader after 65535 loop iterations, even for a path traced alone); "
                         "their light is lost, so results are biased low: use the embree backend "
                         "for this scene");
  }
  add_opening_warnings(r);
  if (r.partial) r.warnings.push_back("run stopped early: results are from the photons traced");
  if (r.decide && r.verdict == VerdictKind::Undecided) {
    r.warnings.push_back(
        "the run ended before every verdict was decided; each undecided one says what "
        "deciding it would cost (to_decide)");
  }
  if (r.target_accuracy && !r.accuracy_met && r.stop_reason == kStopPhotons) {
    r.warnings.push_back(std::string("the photon budget ran out before every ") +
                         (r.accuracy_per_cell ? "cell" : "target") +
                         " reached the requested accuracy");
  }
}

}  // namespace lightsolver::detail
