// What each luminaire group's trace depends on, and the traces kept (group_traces.hpp).
#include "optimizer/group_traces.hpp"

#include <algorithm>
#include <set>

namespace lightsolver::optimizer::reuse {
namespace {

// The domain dimensions a scene variable owns: a rectangle two (u, v), the others one.
std::pair<std::size_t, std::size_t> dimensions_of(const SceneVariable& v) {
  const bool two =
      v.type == SceneVariable::Type::kPosition || v.type == SceneVariable::Type::kTranslation;
  return {v.first, v.first + (two ? 2 : 1)};
}

double largest_level(const Variable& v) {
  double top = 0.0;
  for (std::uint32_t c = 0; c < v.size(); ++c) top = std::max(top, v.value(c));
  return top;
}

}  // namespace

TracePlan plan_traces(const SceneProblem& p, const std::vector<LuminaireGroup>& groups,
                      bool reuse) {
  TracePlan plan;
  plan.depends.assign(groups.size(), std::vector<bool>(p.domain.dimensions(), !reuse));
  plan.scaled_by.assign(groups.size(), -1);
  plan.reference_lm.assign(p.variables.size(), -1.0);
  if (!reuse) return plan;
  std::vector<std::size_t> group_of(p.scene.luminaires.size(), 0);
  for (std::size_t g = 0; g < groups.size(); ++g) {
    for (std::size_t l : groups[g].luminaires) group_of[l] = g;
  }
  auto touch = [&](std::size_t g, const SceneVariable& v) {
    const auto [from, to] = dimensions_of(v);
    for (std::size_t d = from; d < to; ++d) plan.depends[g][d] = true;
  };
  for (std::size_t vi = 0; vi < p.variables.size(); ++vi) {
    const SceneVariable& v = p.variables[vi];
    using T = SceneVariable::Type;
    if (v.type == T::kTranslation || v.type == T::kRotation) {  // every group sees the meshes
      for (std::size_t g = 0; g < groups.size(); ++g) touch(g, v);
    } else if (v.type == T::kPosition || v.type == T::kAim) {
      for (std::size_t l : v.luminaires) touch(group_of[l], v);
    } else {  // flux: scales the groups it sets whole; a group it sets in part is re-traced
      std::set<std::size_t> touched;
      for (std::size_t l : v.luminaires) touched.insert(group_of[l]);
      const bool whole = std::all_of(touched.begin(), touched.end(), [&](std::size_t g) {
        return std::all_of(
            groups[g].luminaires.begin(), groups[g].luminaires.end(), [&](std::size_t l) {
              return std::find(v.luminaires.begin(), v.luminaires.end(), l) != v.luminaires.end();
            });
      });
      for (std::size_t g : touched) {
        if (whole) {
          plan.scaled_by[g] = int(vi);
        } else {
          touch(g, v);
        }
      }
      if (whole) plan.reference_lm[vi] = largest_level(p.domain.variables()[v.first]);
    }
  }
  return plan;
}

std::vector<double> trace_values(const SceneProblem& p, const TracePlan& plan,
                                 const std::vector<double>& values) {
  std::vector<double> out = values;
  for (std::size_t vi = 0; vi < p.variables.size(); ++vi) {
    if (plan.reference_lm[vi] >= 0.0) out.at(p.variables[vi].first) = plan.reference_lm[vi];
  }
  return out;
}

double flux_factor(const SceneProblem& p, const TracePlan& plan, std::size_t group,
                   const std::vector<double>& values) {
  const int v = plan.scaled_by[group];
  if (v < 0) return 1.0;
  const double reference = plan.reference_lm[std::size_t(v)];
  return reference > 0.0 ? values.at(p.variables[std::size_t(v)].first) / reference : 0.0;
}

double installed_flux_lm(const SceneProblem& p, const TracePlan& plan, const Scene& traced,
                         const std::vector<double>& values) {
  std::vector<double> flux;
  for (const Luminaire& l : traced.luminaires) flux.push_back(l.flux_lm);
  for (std::size_t vi = 0; vi < p.variables.size(); ++vi) {
    if (plan.reference_lm[vi] < 0.0) continue;
    for (std::size_t l : p.variables[vi].luminaires) flux[l] = values.at(p.variables[vi].first);
  }
  double sum = 0.0;
  for (double f : flux) sum += f;
  return sum;
}

std::uint64_t sub_configuration(const Domain& d, const TracePlan& plan, std::size_t group,
                                const Configuration& cells) {
  Configuration masked = cells;
  for (std::size_t i = 0; i < masked.size(); ++i) {
    if (!plan.depends[group][i]) masked[i] = 0;
  }
  return d.index(masked);
}

std::size_t TraceCache::Hash::operator()(const Key& k) const {
  std::uint64_t h = k.group * 0x9E3779B97F4A7C15ull;
  h ^= k.sub + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
  h ^= k.photons + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
  h ^= k.level + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
  return static_cast<std::size_t>(h);
}

std::shared_ptr<const GroupTrace> TraceCache::find(const Key& k) {
  const auto it = map_.find(k);
  if (it == map_.end()) return nullptr;
  order_.splice(order_.begin(), order_, it->second);  // now the most recently used
  return it->second->second;
}

void TraceCache::insert(const Key& k, std::shared_ptr<const GroupTrace> t) {
  const auto size = [](const GroupTrace& g) {
    return sizeof(GroupTrace) + g.bins.size() * sizeof(Tally) +
           g.direct.size() * sizeof(DirectLight);
  };
  if (map_.count(k)) return;
  if (k.level > k.photons) {
    std::uint64_t& most = prefixes_[Key{k.group, k.sub, 0, k.level}];
    most = std::max(most, k.photons);
  }
  bytes_ += size(*t);
  order_.emplace_front(k, std::move(t));
  map_[k] = order_.begin();
  while (bytes_ > max_bytes_ && order_.size() > 1) {
    bytes_ -= size(*order_.back().second);
    map_.erase(order_.back().first);
    order_.pop_back();
  }
}

std::shared_ptr<const GroupTrace> TraceCache::find_prefix(const Key& k) {
  const auto it = prefixes_.find(Key{k.group, k.sub, 0, k.level});
  if (it == prefixes_.end() || it->second >= k.photons) return nullptr;
  return find(Key{k.group, k.sub, it->second, k.level});  // null when dropped since
}

}  // namespace lightsolver::optimizer::reuse
