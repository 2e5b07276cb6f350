#pragma once
// Electric light beside a year of daylight (docs/daylight.md, "Electric light beside daylight"):
// the hours the electric lighting must supplement daylight to keep the task's illuminance, and
// the mean output a daylight-linked dimmer would need: an input for LENI's daylight dependency.
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "lightsolver/annual.hpp"
#include "lightsolver/process_group.hpp"
#include "lightsolver/scene.hpp"
#include "lightsolver/solver.hpp"

namespace lightsolver {

/// The task illuminance when a grid states none (EN 12464-1's office writing and reading).
inline constexpr double kDefaultTaskLux = 500.0;

/// One grid's year with its electric lighting.
struct ElectricYear {
  double target_lx = kDefaultTaskLux;  ///< the grid's em_lux requirement, else 500 lx
  Estimate electric_lx;                ///< the electric light's grid mean at full output
  int occupied_hours = 0;
  /// Occupied hours whose daylight (the grid's mean) is below the target: the lights must help.
  MetricInterval hours_on;
  /// The mean over occupied hours of clamp((target − daylight) / electric, 0, 1): the output a
  /// daylight-linked dimmer would need, 1 for lights always on at full output.
  MetricInterval dimming;
  double z_hour = 0.0;  ///< the per-hour critical value (α/2 over the occupied hours)
};

/// The scene's electric luminaires (every one not `sky` or `sun`) lighting its grids, traced at
/// `confidence`; none when the scene has no electric luminaire.
std::optional<Results> trace_electric(const Scene& scene, std::uint64_t photons,
                                      std::optional<std::uint64_t> seed, const std::string& backend,
                                      int threads, double confidence,
                                      std::shared_ptr<ProcessGroup> processes = nullptr);

/// `electric`: the grid's electric estimate with its interval at 1 − α/2; `day` its hours. The
/// counts' ends take each hour at α/(2 H): Bonferroni over the hours and the electric estimate,
/// the grid mean's ends the area-weighted mean of the cells' (conservative whatever their
/// correlation). InputError for a mask without an occupied hour.
ElectricYear electric_year(const Target& grid, const Estimate& electric, const HourlyGrid& day,
                           const std::vector<std::uint8_t>& occupied, double confidence);

nlohmann::json electric_json(const ElectricYear& y);

}  // namespace lightsolver
