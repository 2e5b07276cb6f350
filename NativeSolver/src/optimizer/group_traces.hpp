#pragma once
// Reused traces (docs/optimization.md, "Reused traces"): each luminaire group has its own
// photon stream, and light is linear in a group's flux, so a configuration's results are the
// sum of its groups' traces, each scaled to the group's flux. A group's trace depends only on
// the variables that move or aim its luminaires, the meshes' moves, and flux variables that set
// only part of it; it is traced once per such sub-configuration and photon level and kept.
#include <cstdint>
#include <list>
#include <memory>
#include <unordered_map>
#include <vector>

#include "lightsolver/optimizer/scene_problem.hpp"

namespace lightsolver::optimizer::reuse {

/// What each group's trace depends on, fixed for a search.
struct TracePlan {
  /// [group][domain dimension]: the cells of that dimension select the group's trace.
  std::vector<std::vector<bool>> depends;
  /// Per group: the flux variable (index into SceneProblem::variables) whose level scales its
  /// trace, or -1 (its flux is fixed, or it is traced at the flux the configuration sets).
  std::vector<int> scaled_by;
  /// Per SceneProblem variable: a flux variable's largest level (its groups are traced there).
  std::vector<double> reference_lm;
};

/// `reuse` false: every group depends on every variable and nothing is scaled, so every
/// evaluation traces every group with the request's seed (a plain run, bit for bit).
TracePlan plan_traces(const SceneProblem& p, const std::vector<LuminaireGroup>& groups, bool reuse);

/// The values a configuration's groups are traced at: scaling flux variables at their
/// reference level.
std::vector<double> trace_values(const SceneProblem& p, const TracePlan& plan,
                                 const std::vector<double>& values);

/// Group g's flux now over its flux as traced (1 when nothing scales it).
double flux_factor(const SceneProblem& p, const TracePlan& plan, std::size_t group,
                   const std::vector<double>& values);

/// The luminaires' flux summed as the configuration sets it (`traced`: the scene as traced,
/// scaling flux variables at their reference level), in the order Scene::total_flux_lm sums.
double installed_flux_lm(const SceneProblem& p, const TracePlan& plan, const Scene& traced,
                         const std::vector<double>& values);

/// Index of the group's sub-configuration: Domain::index of the cells with every dimension it
/// does not depend on at 0 (so a group that depends on every variable has the cell's index and
/// the request's own seed).
std::uint64_t sub_configuration(const Domain& d, const TracePlan& plan, std::size_t group,
                                const Configuration& cells);

/// Group traces by (group, sub-configuration, photons, seed level), least recently used
/// dropped beyond a memory budget. Dropping changes no result: a trace is a function of its
/// key. `level`: the photon level whose seed the trace has (its photons, or more for the first
/// stage of a staged refinement, whose trace the level's continues).
class TraceCache {
 public:
  struct Key {
    std::uint64_t group, sub, photons, level;
    bool operator==(const Key&) const = default;
  };
  explicit TraceCache(std::size_t max_bytes) : max_bytes_(max_bytes) {}
  std::shared_ptr<const GroupTrace> find(const Key& k);
  void insert(const Key& k, std::shared_ptr<const GroupTrace> t);
  /// The kept trace with the most photons below `k.photons` that has k's group,
  /// sub-configuration and seed level `k.level`: the first part of k's trace (null: none), e.g.
  /// a staged refinement's N/4 trace for its N/2 stage or its N trace.
  std::shared_ptr<const GroupTrace> find_prefix(const Key& k);
  std::size_t bytes() const { return bytes_; }

 private:
  struct Hash {
    std::size_t operator()(const Key& k) const;
  };
  using Entry = std::pair<Key, std::shared_ptr<const GroupTrace>>;
  std::list<Entry> order_;  // most recently used first
  std::unordered_map<Key, std::list<Entry>::iterator, Hash> map_;
  // (group, sub, level) -> photons of the first-stage traces inserted with a level above them.
  std::unordered_map<Key, std::uint64_t, Hash> prefixes_;
  std::size_t max_bytes_, bytes_ = 0;
};

}  // namespace lightsolver::optimizer::reuse
