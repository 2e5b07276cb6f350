// The target-type table: core's rows (target_types.cpp) with the glare layer's result hooks
// (src/glare/observer_rows.cpp) put in, and the glare rescale reads back (results_glare.hpp).
// An explicit list, as backend_list.cpp is for the backends: core declares target_types() and
// never includes glare; no row depends on static-initialisation order.
#include <stdexcept>
#include <string>
#include <vector>

#include "estimate/daylight_factor.hpp"
#include "results/results_glare.hpp"
#include "types/target_types.hpp"
#include "glare/glare_results_io.hpp"
#include "glare/observer_rows.hpp"

namespace lightsolver::detail {
namespace {

// The result hooks of the layers above core, by type.
struct ResultHook {
  Target::Type type;
  void (*result)(const TargetTallies& tallies, TargetResult& r);
};
constexpr ResultHook kGlareResults[] = {
    {Target::Type::Observer, observer_result},
    {Target::Type::ObserverGrid, observer_grid_result},
};

// The grid row's own result (types/target_types.cpp), then a daylight-factor grid's daylight
// factor from the estimate layer (estimate/daylight_factor.cpp), which types may not include.
void (*core_grid_result)(const TargetTallies&, TargetResult&) = nullptr;

void grid_result_with_daylight_factor(const TargetTallies& tt, TargetResult& r) {
  core_grid_result(tt, r);
  if (tt.target.quantity == Target::Quantity::DaylightFactor && tt.daylight != nullptr) {
    r.daylight_factor = daylight_factor_result(tt);
  }
}

std::vector<TargetType> assemble() {
  const std::span<const TargetType> core = core_target_rows();
  std::vector<TargetType> rows(core.begin(), core.end());
  for (TargetType& row : rows) {
    for (const ResultHook& hook : kGlareResults) {
      if (hook.type == row.type) row.result = hook.result;
    }
    if (row.type == Target::Type::Grid && row.result != nullptr) {
      core_grid_result = row.result;
      row.result = grid_result_with_daylight_factor;
    }
    if (row.result == nullptr) {
      throw std::logic_error(std::string("target type \"") + row.name +
                             "\" has no result hook (src/tables/target_table.cpp)");
    }
  }
  return rows;
}

}  // namespace

std::span<const TargetType> target_types() {
  static const std::vector<TargetType> rows = assemble();
  return rows;
}

const ResultsGlare& results_glare() {
  static const ResultsGlare hooks{dimmed_observer_grid, observer_grid_points,
                                  dimmed_observer_glare};
  return hooks;
}

}  // namespace lightsolver::detail
