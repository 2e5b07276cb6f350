#pragma once
// Estimates of a quasi-random run (docs/statistics.md, "Quasi-random photons"): R independent
// randomisations (replicates) of the same Sobol' points, each with its own tallies. A bin's
// estimate is the mean of the replicates' estimates and its interval Student-t with R - 1
// degrees of freedom from their spread: the per-path variance formula does not apply, since
// the paths of one replicate are not independent. A next-event group's direct part is one
// stratified estimate for the whole run, added to the replicates' mean with its own variance.
#include <cstdint>
#include <optional>
#include <span>

#include "lightsolver/statistics.hpp"

namespace lightsolver::detail {

struct GroupedTallies;

/// Two-sided Student-t critical value with `dof` degrees of freedom at the confidence whose
/// normal critical value is `z` (P(|Z| <= z) = P(|T| <= t)).
double student_t_for_z(double z, std::uint32_t dof);

/// Mean of `values` (the replicates' estimates, at least 2) with the interval mean ± t s / √R,
/// t = student_t_for_z(z, R - 1), the lower end clamped at 0. `hits`: the pooled deposits.
Estimate replicate_interval(std::span<const double> values, double z, std::uint64_t hits);

/// Bin `bin` of a replicate run's tallies (t.replicates > 1): every lit group's part
/// (`group` empty) or one group's. Where no replicate has a hit, the upper end is the zero-hit
/// Wilson bound of the pooled photons (else the interval would be the point 0). Groups with a
/// direct part (next-event estimation: t.direct) add it once, shared by the replicates and
/// independent of them: the photon part's Student-t interval and the direct parts' z·√Var
/// combine as with_direct_part() combines them (the ends' distances in quadrature).
Estimate replicate_estimate(const GroupedTallies& t, std::optional<std::size_t> group,
                            std::uint32_t bin, double area_m2, double z);

}  // namespace lightsolver::detail
