#pragma once
/// \file annual.hpp
/// Annual daylight metrics of one grid from a year of hourly illuminance with intervals
/// (docs/daylight.md, "A year of daylight: annual metrics"; the intervals: docs/statistics.md,
/// "Annual metrics"): daylight autonomy DA, spatial daylight autonomy sDA and annual sunlight
/// exposure ASE (IES LM-83), useful daylight illuminance UDI (Nabil & Mardaljevic), hours above
/// thresholds, and EN 17037's illuminance method. Pure functions over arrays: no tracing.

#include <cstdint>
#include <nlohmann/json_fwd.hpp>
#include <vector>

#include "lightsolver/compliance.hpp"

namespace lightsolver {

/// One grid's hourly illuminance over a year: hours × cells, row-major (hour-major), float32.
/// At hour h, cell c the interval at two-sided standard-normal critical value z is
/// [mean − z·spread_low, mean + z·spread_high] (clamped at 0 below): the spreads are the groups'
/// interval ends (their distances to their own ends, root-sum-squared over the groups, each
/// scaled by the hour's weight) divided by the z they were computed at. Linear scaling in z is
/// exact for normal ends and conservative for Wilson ends taken at a larger z (the caller takes
/// them at the strictest level the metrics use: annual_strictest_z).
struct HourlyGrid {
  int hours = 0, cells = 0;
  std::vector<float> mean, spread_low, spread_high;  // hours × cells, lx, ≥ 0
  std::vector<double> cell_area_m2;                  // cells
};

/// The metrics' thresholds; the defaults are IES LM-83-12's, Nabil & Mardaljevic's and
/// EN 17037:2018's.
struct AnnualOptions {
  double confidence = 0.95;            ///< of every interval, in (0, 1)
  double da_threshold_lx = 300.0;      ///< DA_T: an occupied hour counts when E ≥ T
  double sda_fraction = 0.5;           ///< sDA_T/f: a cell counts when DA ≥ f
  double sda_nominal = 0.55;           ///< LM-83's "nominally accepted" sDA (area fraction)
  double sda_preferred = 0.75;         ///< LM-83's "preferred" sDA
  double ase_direct_lx = 1000.0;       ///< ASE: direct sun above this (lx) …
  int ase_hours = 250;                 ///< … for more than this many occupied hours
  double ase_maximum = 0.10;           ///< LM-83's satisfactory ASE: at most this area fraction
  double blinds_direct_lx = 1000.0;    ///< blinds close when direct sun above this (lx) …
  double blinds_area_fraction = 0.02;  ///< … reaches more than this area fraction
  double udi_low_lx = 100.0;           ///< UDI: below it "fell short"
  double udi_high_lx = 2000.0;         ///< UDI: above it "exceeded" (useful: low ≤ E ≤ high)
  double udi_high_alt_lx = 3000.0;     ///< the upper limit also reported
  /// Hours above thresholds: occupied hours with E ≥ T, per cell, for each T (lx).
  std::vector<double> hour_thresholds_lx = {100.0, 300.0, 500.0, 750.0, 1000.0, 2000.0, 3000.0};
  double en17037_hours = 0.5;          ///< EN 17037: the fraction of daylight hours required
  double en17037_target_area = 0.5;    ///< E_T over this area fraction
  double en17037_minimum_area = 0.95;  ///< E_TM over this area fraction
};

/// A metric and its interval at AnnualOptions::confidence: low ≤ estimate ≤ high, all finite.
struct MetricInterval {
  double estimate = 0.0, low = 0.0, high = 0.0;
};

/// One cell's metrics. Fractions are of the occupied hours (DA, UDI), hours are occupied hours.
/// The intervals hold at the confidence for this cell (each of its occupied hours at one-sided
/// alpha / (2 H)); sda is decided at the grid's level (all cell-hours at once).
struct AnnualCellMetrics {
  MetricInterval da;  ///< fraction of occupied hours with E ≥ da_threshold_lx
  VerdictKind sda = VerdictKind::Undecided;  ///< DA ≥ sda_fraction (the grid-level interval)
  MetricInterval udi_below;                  ///< E < udi_low_lx
  MetricInterval udi_useful;                 ///< udi_low_lx ≤ E ≤ udi_high_lx
  MetricInterval udi_above;                  ///< E > udi_high_lx
  MetricInterval udi_useful_alt;             ///< udi_low_lx ≤ E ≤ udi_high_alt_lx
  MetricInterval udi_above_alt;              ///< E > udi_high_alt_lx
  std::vector<MetricInterval> hours_above;   ///< per hour_thresholds_lx: hours with E ≥ T
  int ase_hours = 0;  ///< occupied hours with direct sun > ase_direct_lx (exact; 0 without sun)
};

/// EN 17037's illuminance method at one level: two criteria, each a fraction of the daylight
/// hours at which the grid reaches an illuminance over an area fraction, required ≥
/// en17037_hours.
struct En17037Criterion {
  double illuminance_lx = 0.0;  ///< E_T or E_TM
  double area_fraction = 0.0;   ///< 0.5 or 0.95
  MetricInterval hours_fraction;
  VerdictKind verdict = VerdictKind::Undecided;
};

/// One EN 17037 level (minimum: 300/100 lx, medium: 500/300, high: 750/500).
struct En17037Illuminance {
  En17037Level level = En17037Level::Minimum;
  En17037Criterion target;                       ///< E_T over en17037_target_area
  En17037Criterion minimum;                      ///< E_TM over en17037_minimum_area
  VerdictKind verdict = VerdictKind::Undecided;  ///< both criteria (overall())
};

/// One grid's annual metrics.
struct AnnualMetrics {
  AnnualOptions options;
  int hours = 0, cells = 0;
  int occupied_hours = 0, daylight_hours = 0;
  double area_m2 = 0.0;
  /// The critical values used: per cell (alpha / H per hour, two-sided), per grid (alpha /
  /// (cells · H)).
  double z_cell = 0.0, z_grid = 0.0;
  bool blinds_given = false;
  int blinds_closed_hours = 0;  ///< occupied hours the LM-83 blinds rule closed the blinds
  MetricInterval sda;           ///< area fraction of cells with DA ≥ sda_fraction
  VerdictKind sda_nominal = VerdictKind::Undecided, sda_preferred = VerdictKind::Undecided;
  /// Area-weighted means over the cells (grid-level intervals).
  MetricInterval da, udi_below, udi_useful, udi_above, udi_useful_alt, udi_above_alt;
  std::vector<MetricInterval> hours_above;  ///< per threshold: the area-weighted mean hours
  bool sun_given = false;  ///< direct_sun_lx given: ASE computed (exactly, no interval)
  double ase = 0.0;        ///< area fraction with ase_hours > options.ase_hours
  VerdictKind ase_verdict = VerdictKind::Undecided;  ///< ase ≤ ase_maximum (pass or fail)
  std::vector<En17037Illuminance> en17037;           ///< minimum, medium, high
  std::vector<AnnualCellMetrics> cell;
};

/// The metrics of `grid` (docs/daylight.md, "A year of daylight: annual metrics").
/// `occupied` and `daylight_hour`: per hour, 1 or 0 (lm83_occupancy, en17037_daylight_hours).
/// `direct_sun_lx`: hours × cells of direct sun only (lx), or empty when the scene has no sun
/// (no ASE, no blinds rule). `blinds_closed`: the same grid with the blinds closed, or null;
/// with it, an occupied hour at which more than blinds_area_fraction of the area gets more than
/// blinds_direct_lx of direct sun takes its DA (and so sDA) values from it (LM-83). UDI, hours
/// above and EN 17037 use `grid` as given. InputError naming the field for sizes that do not
/// match, negative or non-finite values, a mask without an hour, or cells of unequal area
/// (EN 17037's area fractions are ranks of equal cells).
AnnualMetrics annual_metrics(const HourlyGrid& grid, const std::vector<std::uint8_t>& occupied,
                             const std::vector<std::uint8_t>& daylight_hour,
                             const std::vector<float>& direct_sun_lx,
                             const AnnualOptions& options = {},
                             const HourlyGrid* blinds_closed = nullptr);

/// The largest critical value annual_metrics uses for these counts: the level at which the
/// caller should take Wilson ends before scaling them to spreads (HourlyGrid).
double annual_strictest_z(const AnnualOptions& options, int occupied_hours, int daylight_hours,
                          int cells);

/// LM-83's occupancy, 8:00–18:00 local standard time every day: 1 for the EPW rows with hour
/// stamp first … last (9 … 18: a row describes the hour ending at its stamp), 3650 of 8760.
/// InputError naming `hour_stamps[i]` for a stamp outside 1 … 24.
std::vector<std::uint8_t> lm83_occupancy(const std::vector<int>& hour_stamps, int first = 9,
                                         int last = 18);

/// The `metrics` object of one grid in annual.json: grid-level values (sda_percent,
/// ase_percent, da_fraction, udi_*_fraction, hours_above, en17037) and per-cell arrays under
/// "cells" (docs/daylight.md, "A year of daylight: annual metrics").
nlohmann::json annual_metrics_json(const AnnualMetrics& m);

}  // namespace lightsolver
