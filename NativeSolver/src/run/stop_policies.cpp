// A run's stopping rules and batch observers (stop_policies.hpp).
#include "run/stop_policies.hpp"

#include <algorithm>
#include <bit>

namespace lightsolver::detail {

std::uint64_t TimeLimit::fit(std::uint64_t n, double photons_per_second, double elapsed_s) const {
  if (!max_seconds_ || !(photons_per_second > 0.0)) return n;
  const double seconds_left = *max_seconds_ - elapsed_s;
  const double fits = std::max(photons_per_second * seconds_left, double(1u << 14));
  return fits < double(n) ? static_cast<std::uint64_t>(fits) : n;
}

bool DecidePolicy::stop_after(const BatchState& s) {
  if (!enabled_ || !std::has_single_bit(s.photons)) return false;
  return all_decided_(s.photons, ++looks_);
}

std::uint64_t StopPolicies::before(const BatchState& s) const {
  for (std::size_t i = 0; i < policies_.size(); ++i) {
    if (policies_[i]->stop_before(s)) return i + 1;
  }
  return 0;
}

std::uint64_t StopPolicies::after(const BatchState& s) const {
  for (std::size_t i = 0; i < policies_.size(); ++i) {
    if (policies_[i]->stop_after(s)) return i + 1;
  }
  return 0;
}

void ForecastObserver::after_batch(const BatchState& s) {
  if (!due_ || !(s.elapsed_s >= 0.5) || s.photons >= s.requested) return;
  due_ = false;
  emit_(s);
}

}  // namespace lightsolver::detail
