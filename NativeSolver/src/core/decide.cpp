// Verdicts per target and the rule that ends a decide run (docs/statistics.md, "Deciding").
#include "core/decide.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

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

// One verdict per requirement, em first. A grid's U0, Emin and Ud use the honest intervals of
// grid_intervals(); Em uses the target's own interval.
std::vector<Verdict> verdicts_of(const TargetResult& t) {
  const Requirements& q = t.requirements;
  std::vector<Verdict> out;
  const Estimate& e = t.estimate;
  if (q.em_lux) out.push_back(make_verdict("em", e.mean, e.ci_low, e.ci_high, *q.em_lux));
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

std::uint64_t photons_to_decide_all(std::vector<TargetResult>& targets, std::uint64_t photons,
                                    std::uint64_t budget) {
  all_decided(targets);  // judges them
  double most = double(photons);
  for (const TargetResult& t : targets) {
    for (const Verdict& v : t.verdicts) {
      if (v.verdict != VerdictKind::Undecided) continue;
      const auto need = photons_to_decide(v.value, v.ci_low, v.ci_high, v.required, photons);
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
      v.photons_to_decide = photons_to_decide(v.value, v.ci_low, v.ci_high, v.required, r.photons);
      if (v.photons_to_decide && photons_per_second > 0.0) {
        v.seconds_to_decide = *v.photons_to_decide / photons_per_second;
      }
    }
  }
}

}  // namespace lightsolver::detail
