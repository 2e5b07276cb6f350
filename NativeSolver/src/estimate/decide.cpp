// Verdicts per target and the rule that ends a decide run (docs/statistics.md, "Deciding").
#include "estimate/decide.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

namespace lightsolver::detail {
namespace {

Verdict make_verdict(const char* name, double value, double low, double high, double required) {
  Verdict v;
  v.name = name;
  v.value = value;
  v.ci_low = low;
  v.ci_high = high;
  v.required = required;
  v.verdict = judge(low, high, required);
  return v;
}

// UGR <= ugr_max from the UGR interval (docs/glare.md). No luminaire counting: no glare, a
// pass at any limit (value unknown: "< 10" on data sheets). An interval open above (L_b's lower
// end 0) can fail but not pass.
Verdict ugr_verdict(const ObserverGlare& g, double required) {
  Verdict v;
  v.name = "ugr";
  v.relation = "<=";
  v.required = required;
  const bool no_glare = !(g.luminaire_sum > 0.0);
  v.value_known = g.ugr.has_value();
  v.value = g.ugr.value_or(0.0);
  v.ci_high_known = g.ugr_ci_high.has_value();
  v.ci_high = g.ugr_ci_high.value_or(0.0);
  v.ci_low = g.ugr_ci_low.value_or(0.0);
  if (no_glare) {
    v.ci_high_known = v.value_known = false;
    v.verdict = VerdictKind::Pass;
  } else if (!g.ugr_ci_low) {
    v.verdict = VerdictKind::Undecided;  // nothing measured yet: L_b's upper end is 0
    v.ci_high_known = false;
  } else if (!v.ci_high_known) {
    v.verdict = *g.ugr_ci_low > required ? VerdictKind::Fail : VerdictKind::Undecided;
  } else {
    v.verdict = judge_at_most(v.ci_low, v.ci_high, required);
  }
  return v;
}

// One verdict per requirement, em first. A grid's U0, Emin and Ud use the honest intervals of
// grid_intervals(); Em uses the target's own interval. A daylight-factor grid's D_T and D_TM
// judge the values reached over 50 % and 95 % of its area (order statistics' intervals).
std::vector<Verdict> verdicts_of(const TargetResult& t) {
  const Requirements& q = t.requirements;
  std::vector<Verdict> out;
  const Estimate& e = t.estimate;
  if (t.daylight_factor) {  // a daylight-factor grid takes these alone (validate())
    const DaylightFactorResult& d = *t.daylight_factor;
    if (const auto r = q.df_target()) {
      out.push_back(make_verdict("df_target", d.p50.value, d.p50.low, d.p50.high, *r));
    }
    if (const auto r = q.df_minimum()) {
      out.push_back(make_verdict("df_minimum", d.p95.value, d.p95.low, d.p95.high, *r));
    }
    return out;
  }
  if (q.em_lux) out.push_back(make_verdict("em", e.mean, e.ci_low, e.ci_high, *q.em_lux));
  if (q.ugr_max && t.glare) out.push_back(ugr_verdict(*t.glare, *q.ugr_max));
  if (!t.intervals) return out;  // a surface: em only (validate() refuses the others)
  const GridIntervals& g = *t.intervals;
  if (q.u0) out.push_back(make_verdict("u0", t.uniformity, g.u0_low, g.u0_high, *q.u0));
  if (q.emin_lux) {
    out.push_back(make_verdict("emin", t.min_lux, g.min_low, g.min_high, *q.emin_lux));
  }
  if (q.ud) out.push_back(make_verdict("ud", g.ud, g.ud_low, g.ud_high, *q.ud));
  return out;
}

void judge_target(TargetResult& t) {
  if (!t.requirements.any()) return;
  t.verdicts = verdicts_of(t);
  std::vector<VerdictKind> kinds;
  for (const Verdict& v : t.verdicts) kinds.push_back(v.verdict);
  t.verdict = overall(kinds);
}

}  // namespace

double look_confidence(double confidence, int look) {
  const double k = std::max(look, 1);
  return 1.0 - (1.0 - confidence) * 6.0 / (std::numbers::pi * std::numbers::pi * k * k);
}

bool judges_requirements(const Scene& scene, bool decide, bool accuracy_goal) {
  bool any = false;
  for (const Target& t : scene.targets) any = any || t.requirements.any();
  if (decide && !any) {
    throw InputError(scene.source_file, "decide",
                     "no target has requirements to decide (give a target \"requirements\" or "
                     "a \"task\")");
  }
  if (decide && accuracy_goal) {
    throw InputError(scene.source_file, "decide",
                     "give either an accuracy goal or decide, not both: deciding stops as soon "
                     "as every verdict is pass or fail");
  }
  return any;
}

void add_verdicts(Results& r) {
  std::vector<VerdictKind> kinds;
  for (TargetResult& t : r.targets) {
    judge_target(t);
    if (t.requirements.any()) kinds.push_back(t.verdict);
  }
  r.verdict = overall(kinds);
}

bool all_decided(std::vector<TargetResult>& targets) {
  bool decided = true;
  for (TargetResult& t : targets) {  // every target judged, even after an undecided one
    judge_target(t);
    for (const Verdict& v : t.verdicts) decided = decided && v.verdict != VerdictKind::Undecided;
  }
  return decided;
}

std::optional<double> photons_to_decide(double value, double low, double high, double required,
                                        std::uint64_t photons) {
  const double distance = std::abs(value - required);
  const double half_width = value >= required ? value - low : high - value;
  if (photons == 0 || !(distance > 0.0)) return std::nullopt;
  const double ratio = half_width / distance;
  const double need = double(photons) * ratio * ratio;
  if (!std::isfinite(need)) return std::nullopt;
  return std::max(need, double(photons));
}

namespace {

// photons_to_decide() for either relation: "<=" mirrors the axis; an interval open above or
// without a value gives no estimate.
std::optional<double> photons_for(const Verdict& v, std::uint64_t photons) {
  if (!v.value_known || !v.ci_high_known) return std::nullopt;
  if (std::string(v.relation) == "<=") {
    return photons_to_decide(-v.value, -v.ci_high, -v.ci_low, -v.required, photons);
  }
  return photons_to_decide(v.value, v.ci_low, v.ci_high, v.required, photons);
}

}  // namespace

std::uint64_t photons_to_decide_all(std::vector<TargetResult>& targets, std::uint64_t photons,
                                    std::uint64_t budget) {
  all_decided(targets);  // judges them
  double most = double(photons);
  for (const TargetResult& t : targets) {
    for (const Verdict& v : t.verdicts) {
      if (v.verdict != VerdictKind::Undecided) continue;
      const auto need = photons_for(v, photons);
      if (!need) return budget;
      most = std::max(most, *need);
    }
  }
  return most >= double(budget) ? budget : static_cast<std::uint64_t>(most);
}

void add_to_decide(Results& r, double photons_per_second) {
  for (TargetResult& t : r.targets) {
    for (Verdict& v : t.verdicts) {
      if (v.verdict != VerdictKind::Undecided) continue;
      v.photons_to_decide = photons_for(v, r.photons);
      if (v.photons_to_decide && photons_per_second > 0.0) {
        v.seconds_to_decide = *v.photons_to_decide / photons_per_second;
      }
    }
  }
}

}  // namespace lightsolver::detail
