#include "lightsolver/optimizer/isoc.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace lightsolver::optimizer {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

Relation flip(Relation r) {
  if (r == Relation::Greater) return Relation::Less;
  if (r == Relation::Less) return Relation::Greater;
  return r;
}

void check_estimate(const Estimate& e) {
  if (std::isnan(e.mean) || std::isnan(e.sigma) || std::isnan(e.ci_low) || std::isnan(e.ci_high))
    throw std::invalid_argument("Isoc::update: estimate has a NaN field");
}

}  // namespace

std::string_view paper_case(UpdateCase c) {
  switch (c) {
    case UpdateCase::kFirst:
      return "init";
    case UpdateCase::kDiscarded:
      return "1";
    case UpdateCase::kRejected:
      return "2a";
    case UpdateCase::kReplaced:
      return "2b";
    case UpdateCase::kJoined:
      return "2c";
    case UpdateCase::kLeads:
      return "3";
  }
  return "?";
}

std::string_view to_string(Region r) {
  switch (r) {
    case Region::kEmpty:
      return "empty";
    case Region::kWorse:
      return "worse";
    case Region::kOverlap:
      return "overlap";
    case Region::kBetter:
      return "better";
  }
  return "?";
}

Isoc::Isoc(Goal goal, double confidence) : goal_(goal), confidence_(confidence) {
  if (!(confidence > 0.0 && confidence < 1.0))
    throw std::invalid_argument("Isoc: confidence must lie in (0, 1)");
  recompute_siisoc();
}

Relation Isoc::oriented(const Estimate& a, const Estimate& b) const {
  const Relation r = compare(a, b, confidence_);
  return goal_ == Goal::kMaximize ? r : flip(r);
}

Region Isoc::classify(const Estimate& c) const {
  if (members_.empty()) return Region::kEmpty;
  // The worse side is tested first: with asymmetric CIs the SIISOC may be empty and a CI could
  // then be on both sides; update() settles that case with compare() anyway.
  if (goal_ == Goal::kMaximize) {
    if (c.ci_high < siisoc_.low) return Region::kWorse;
    if (c.ci_low > siisoc_.high) return Region::kBetter;
  } else {
    if (c.ci_low > siisoc_.high) return Region::kWorse;
    if (c.ci_high < siisoc_.low) return Region::kBetter;
  }
  return Region::kOverlap;
}

std::size_t Isoc::worse_end_member() const {
  // Maximising, the SIISOC's worse end is maxmin: the member with the highest CI low end.
  // Minimising, it is minmax: the member with the lowest CI high end.
  std::size_t w = 0;
  for (std::size_t i = 1; i < members_.size(); ++i) {
    const Estimate& e = members_[i].estimate;
    const Estimate& b = members_[w].estimate;
    if (goal_ == Goal::kMaximize ? e.ci_low > b.ci_low : e.ci_high < b.ci_high) w = i;
  }
  return w;
}

bool Isoc::dominated(const Estimate& c) const {
  if (classify(c) != Region::kWorse) return false;
  return oriented(members_[worse_end_member()].estimate, c) == Relation::Greater;
}

IsocUpdate Isoc::update(std::uint64_t key, const Estimate& c) {
  check_estimate(c);
  erase_key(key);
  IsocUpdate u;
  u.region = classify(c);
  if (members_.empty()) {
    members_.push_back({key, c});
    recompute_siisoc();
    u.result = UpdateCase::kFirst;
    return u;
  }
  if (u.region == Region::kWorse) {
    // State 1. The CI lies beyond the witness's CI; with symmetric intervals that implies the
    // witness beats it, but the Wilson interval is asymmetric, so we confirm with compare().
    // An unconfirmed state 1 falls through to the full comparison of state 2.
    ++u.comparisons;
    if (oriented(members_[worse_end_member()].estimate, c) == Relation::Greater) {
      u.result = UpdateCase::kDiscarded;
      return u;
    }
  }
  std::vector<std::size_t> beaten;
  for (std::size_t i = 0; i < members_.size(); ++i) {
    ++u.comparisons;
    const Relation r = oriented(c, members_[i].estimate);
    if (r == Relation::Less) {
      // Case 2a (corrected): a member beats the candidate, so it stays out. By transitivity no
      // member can then be beaten by it, so stopping at the first such member is safe.
      u.result = UpdateCase::kRejected;
      return u;
    }
    if (r == Relation::Greater) beaten.push_back(i);
  }
  // Case 2b may beat several members: all of them leave. State 3 removes exactly the members
  // that are not =α to the candidate, which (no member beating it) are the beaten ones.
  for (auto it = beaten.rbegin(); it != beaten.rend(); ++it) {
    u.removed.insert(u.removed.begin(), members_[*it].key);
    members_.erase(members_.begin() + static_cast<std::ptrdiff_t>(*it));
  }
  members_.push_back({key, c});
  recompute_siisoc();
  if (u.region == Region::kBetter)
    u.result = UpdateCase::kLeads;
  else
    u.result = beaten.empty() ? UpdateCase::kJoined : UpdateCase::kReplaced;
  return u;
}

bool Isoc::contains(std::uint64_t key) const {
  return std::any_of(members_.begin(), members_.end(),
                     [key](const IsocMember& m) { return m.key == key; });
}

const IsocMember* Isoc::best() const {
  const IsocMember* best = nullptr;
  for (const IsocMember& m : members_) {
    if (!best) {
      best = &m;
      continue;
    }
    const double a = m.estimate.mean, b = best->estimate.mean;
    const bool better = goal_ == Goal::kMaximize ? a > b : a < b;
    if (better || (a == b && m.key < best->key)) best = &m;
  }
  return best;
}

bool Isoc::invariant_holds() const {
  for (std::size_t i = 0; i < members_.size(); ++i)
    for (std::size_t j = i + 1; j < members_.size(); ++j)
      if (!equal_alpha(members_[i].estimate, members_[j].estimate, confidence_)) return false;
  return true;
}

void Isoc::clear() {
  members_.clear();
  recompute_siisoc();
}

void Isoc::erase_key(std::uint64_t key) {
  const auto it = std::find_if(members_.begin(), members_.end(),
                               [key](const IsocMember& m) { return m.key == key; });
  if (it == members_.end()) return;
  members_.erase(it);
  recompute_siisoc();
}

void Isoc::recompute_siisoc() {
  siisoc_ = {-kInf, kInf};
  if (members_.empty()) {
    siisoc_ = {kInf, -kInf};
    return;
  }
  for (const IsocMember& m : members_) {
    siisoc_.low = std::max(siisoc_.low, m.estimate.ci_low);
    siisoc_.high = std::min(siisoc_.high, m.estimate.ci_high);
  }
}

}  // namespace lightsolver::optimizer
