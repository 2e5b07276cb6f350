#pragma once
/// \file isoc.hpp
/// The Indistinguishable Set of Optimum Configurations (ISOC) and its superposition interval
/// (SIISOC) of Avas & Fernández, Sec. III-C, with the update rules of Sec. III-C2 for
/// maximisation and, mirrored, minimisation.
///
/// Invariant (Eq. 10): every pair of members is =α. Because compare() of Eq. 7 is transitive
/// (x >α y >α w implies x >α w), the set reached after any sequence of updates is exactly the
/// set of offered candidates that no other offered candidate beats, whatever the order of the
/// offers (docs/optimization.md explains why).

#include <cstdint>
#include <string_view>
#include <vector>

#include "lightsolver/statistics.hpp"

namespace lightsolver::optimizer {

/// Direction of the optimisation.
enum class Goal { kMaximize, kMinimize };

/// Closed interval [low, high]; empty when low > high.
struct Interval {
  double low = 0.0;
  double high = 0.0;
  bool empty() const { return low > high; }
};

/// Where a candidate's CI lies relative to the SIISOC, read in the goal's direction
/// (the paper's three states; "worse" is "below" when maximising, "above" when minimising).
enum class Region {
  kEmpty,    ///< the ISOC had no member
  kWorse,    ///< state 1: CI entirely on the worse side (max: ci_high < maxmin)
  kOverlap,  ///< state 2: CI intersects the SIISOC
  kBetter,   ///< state 3: CI entirely on the better side (max: ci_low > minmax)
};

/// What an update did. The paper's labels are given by paper_case().
enum class UpdateCase {
  kFirst,      ///< the ISOC was empty: the candidate is its first member
  kDiscarded,  ///< state 1: the member defining the SIISOC's worse end beats the candidate
  kRejected,   ///< case 2a: some member beats the candidate; ISOC unchanged
  kReplaced,   ///< case 2b: the candidate beats one or more members; they leave, it enters
  kJoined,     ///< case 2c: the candidate is =α to every member; it enters
  kLeads,      ///< state 3: the candidate enters; members not =α to it leave
};

/// "init", "1", "2a", "2b", "2c" or "3".
std::string_view paper_case(UpdateCase c);
/// "empty", "worse", "overlap" or "better".
std::string_view to_string(Region r);

/// Report of one update, for tests, logs and counters.
struct IsocUpdate {
  Region region = Region::kEmpty;
  UpdateCase result = UpdateCase::kFirst;
  std::vector<std::uint64_t> removed;  ///< keys of members that left, in member order
  int comparisons = 0;                 ///< calls to compare() this update made
  /// True when the candidate became a member.
  bool admitted() const {
    return result != UpdateCase::kDiscarded && result != UpdateCase::kRejected;
  }
};

/// One member: an opaque key chosen by the caller (the optimizer uses the grid cell index) and
/// the objective estimate it was admitted with.
struct IsocMember {
  std::uint64_t key = 0;
  Estimate estimate;
};

/// The ISOC of one objective. Not thread-safe.
class Isoc {
 public:
  /// \param confidence two-sided level of the =α test, in (0, 1); throws std::invalid_argument
  Isoc(Goal goal, double confidence);

  /// Offers a candidate (Sec. III-C2). If `key` is already a member its old entry is removed
  /// first (a re-evaluation replaces the earlier estimate). Throws std::invalid_argument on a
  /// NaN mean or sigma.
  IsocUpdate update(std::uint64_t key, const Estimate& candidate);

  /// The region of a candidate's CI relative to the SIISOC, without changing anything.
  Region classify(const Estimate& candidate) const;

  /// True when state 1 applies and is confirmed by compare(): a member beats the candidate, so
  /// it would be discarded. Strategy A uses this to decide whether a cheap estimate is worth a
  /// precise one (Sec. IV-A "intersects or is better than the SIISOC" is !dominated()).
  bool dominated(const Estimate& candidate) const;

  /// [maxmin, minmax] over the members' CIs. Meaningless (low = +inf, high = -inf) when empty.
  /// With symmetric CIs it is never empty for a non-empty ISOC (Eq. 12); with asymmetric ones
  /// (Wilson) it may be, and the update rules still hold because they rely on compare().
  Interval siisoc() const { return siisoc_; }

  const std::vector<IsocMember>& members() const { return members_; }
  std::size_t size() const { return members_.size(); }
  bool empty() const { return members_.empty(); }
  bool contains(std::uint64_t key) const;
  /// The member with the best mean in the goal's direction (nullptr when empty); ties go to the
  /// smaller key so the answer does not depend on insertion order.
  const IsocMember* best() const;

  /// Eq. 10, first line: every pair of members is =α. O(size²); for tests and debug checks.
  bool invariant_holds() const;

  Goal goal() const { return goal_; }
  double confidence() const { return confidence_; }
  void clear();

 private:
  /// Greater when `a` is better than `b` in the goal's direction (a >α b when maximising).
  Relation oriented(const Estimate& a, const Estimate& b) const;
  /// Index of the member whose CI end defines the SIISOC end on the worse side.
  std::size_t worse_end_member() const;
  void erase_key(std::uint64_t key);
  void recompute_siisoc();

  Goal goal_;
  double confidence_;
  std::vector<IsocMember> members_;
  Interval siisoc_;
};

}  // namespace lightsolver::optimizer
