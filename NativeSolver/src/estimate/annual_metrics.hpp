#pragma once
// Annual metrics' internals; the API (HourlyGrid, AnnualOptions, annual_metrics, the JSON) is
// the public lightsolver/annual.hpp.
#include <cstdint>
#include <vector>

#include "lightsolver/annual.hpp"

namespace lightsolver::detail {

/// Every input of annual_metrics() checked: InputError naming the field (`grid.mean`,
/// `occupied`, `options.confidence`, ...) for a size that does not match, a negative or
/// non-finite value, a mask without a set hour or with a value other than 0 and 1, blinds
/// without direct sun, or cells of unequal area.
void check_annual_inputs(const HourlyGrid& grid, const std::vector<std::uint8_t>& occupied,
                         const std::vector<std::uint8_t>& daylight_hour,
                         const std::vector<float>& direct_sun_lx, const AnnualOptions& options,
                         const HourlyGrid* blinds_closed);

}  // namespace lightsolver::detail
