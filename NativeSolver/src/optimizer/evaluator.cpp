#include "lightsolver/optimizer/evaluator.hpp"

#include <stdexcept>

namespace lightsolver::optimizer {

namespace {

// SplitMix64 finaliser (Steele et al., OOPSLA'14): a bijection that spreads every input bit.
std::uint64_t mix(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

}  // namespace

std::uint64_t evaluation_seed(std::uint64_t run_seed, std::uint64_t cell_index,
                              std::uint64_t photons) {
  // Chained rather than xor-ed so that swapping the cell index and photon count changes it.
  return mix(mix(mix(run_seed) ^ cell_index) ^ photons);
}

const Evaluation* TabuCache::find(std::uint64_t cell, std::uint64_t photons) const {
  const auto it = map_.find(cell);
  if (it == map_.end()) return nullptr;
  const auto jt = it->second.find(photons);
  return jt == it->second.end() ? nullptr : &jt->second;
}

const Evaluation* TabuCache::most_precise(std::uint64_t cell) const {
  const auto it = map_.find(cell);
  return it == map_.end() ? nullptr : &it->second.rbegin()->second;
}

std::uint64_t TabuCache::most_photons(std::uint64_t cell) const {
  const auto it = map_.find(cell);
  return it == map_.end() ? 0 : it->second.rbegin()->first;
}

const Evaluation& TabuCache::insert(std::uint64_t cell, std::uint64_t photons, Evaluation e) {
  auto [it, fresh] = map_[cell].emplace(photons, std::move(e));
  if (!fresh) throw std::logic_error("TabuCache: cell evaluated twice at the same photon level");
  ++entries_;
  return it->second;
}

}  // namespace lightsolver::optimizer
