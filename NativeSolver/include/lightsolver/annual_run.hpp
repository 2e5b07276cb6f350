#pragma once
/// \file annual_run.hpp
/// A year of daylight (`lightsolver annual`, docs/daylight.md, "Daylight coefficients: a year in
/// one trace"): the weather file's skies, the daylight coefficients traced once, every hour of
/// every grid rebuilt with its interval, and the annual metrics with theirs. What the CLI writes
/// (annual.json and annual.npz) and Python's `lightsolver.annual` returns.

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lightsolver/daylight_coefficients.hpp"
#include "lightsolver/process_group.hpp"
#include "lightsolver/scene.hpp"

namespace lightsolver {

/// What an annual run does.
struct AnnualRunOptions {
  std::filesystem::path weather;  ///< an EPW file
  /// MF, north, irradiance or illuminance; its ground reflectance is the scene's sky's
  /// `ground_reflectance` unless `ground_reflectance` below is given.
  SkyMatrixOptions sky;
  std::optional<double> ground_reflectance;
  std::uint64_t photons = 20'000'000;
  std::optional<std::uint64_t> seed;  ///< default: the scene's settings.seed
  std::string backend = "auto";
  int threads = 0;
  double confidence = 0.95;  ///< of every reported interval
  /// The occupied hours: one 0/1 per hour of the weather file; empty: every day from the EPW
  /// hour stamp `occupied_first` to `occupied_last` (IES LM-83: 9 … 18, i.e. 8:00–18:00).
  std::vector<std::uint8_t> occupancy;
  int occupied_first = 9, occupied_last = 18;
  /// LM-83's blinds rule: with a value, an occupied hour at which more than 2 % of a grid gets
  /// more than 1000 lx of direct sun takes, for DA and sDA, the blinds-closed illuminance: the
  /// sky's light (the sun's beam stopped) times this transmittance. None: blinds open always.
  std::optional<double> blinds_transmittance;
  /// Trace until every grid's verdicts (sDA against 55 % and 75 %, each EN 17037 level) are
  /// decided: looks at photons, 2 × photons, 4 × … up to `max_photons`, look k judged at
  /// confidence 1 − α·6/(π² k²) (alpha spending, docs/statistics.md "Deciding"); the results
  /// are then reported at `confidence` from the last look's trace.
  bool decide = false;
  std::optional<std::uint64_t> max_photons;  ///< decide's budget; default 16 × photons
  /// Called between the trace's batches (photons so far, of the look's total); false stops the
  /// trace there: the year is then computed from the photons traced, its stop reason
  /// "cancelled". The direct sun's shadow rays (a few seconds) run before it and are not cut.
  ProgressFn progress;
  /// MPI ranks sharing the trace (docs/cluster.md): each traces a slice of every batch and all
  /// get the same year; null: this process alone. Every rank calls run_annual alike.
  std::shared_ptr<ProcessGroup> processes;
};

/// One grid's year.
struct AnnualGrid {
  std::string name;
  HourlyIlluminance hourly;  ///< hours × cells with spreads (daylight_coefficients.hpp)
  /// hours × cells, lx: each hour's interval at the run's confidence, per hour.
  std::vector<float> low, high;
  /// hours × cells, lx: direct sun alone (no interreflection) at the cell centres, for ASE;
  /// empty when the year has no sun.
  std::vector<float> direct_sun;
};

/// An annual run's results: `summary` is annual.json (`"format": "lightsolver.annual/1"`).
struct AnnualResult {
  nlohmann::json summary;
  std::vector<AnnualGrid> grids;
  std::vector<std::int32_t> month_day_hour;  ///< hours × 3, the weather file's stamps
};

/// Reads the weather file, traces the coefficients and rebuilds every hour. InputError naming
/// the weather file's line, the option or the scene's field.
AnnualResult run_annual(const Scene& scene, const AnnualRunOptions& options);

}  // namespace lightsolver
