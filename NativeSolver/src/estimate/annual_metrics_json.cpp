// A grid's annual metrics as the `metrics` object of annual.json (docs/daylight.md, "A year of
// daylight: annual metrics"): names carry their unit (_fraction of occupied or daylight hours,
// _percent of the area, _hours, _lx); every interval is {estimate, low, high}.
#include <nlohmann/json.hpp>

#include "estimate/annual_metrics.hpp"

namespace lightsolver {
namespace {

using nlohmann::json;

json interval(const MetricInterval& m, double scale = 1.0) {
  return {{"estimate", m.estimate * scale}, {"low", m.low * scale}, {"high", m.high * scale}};
}

// Per-cell arrays of one interval: {"estimate": [...], "low": [...], "high": [...]}.
template <class Get>
json cell_arrays(const std::vector<AnnualCellMetrics>& cells, Get get) {
  json e = json::array(), lo = json::array(), hi = json::array();
  for (const AnnualCellMetrics& c : cells) {
    const MetricInterval& m = get(c);
    e.push_back(m.estimate);
    lo.push_back(m.low);
    hi.push_back(m.high);
  }
  return {{"estimate", e}, {"low", lo}, {"high", hi}};
}

json criterion(const En17037Criterion& c) {
  return {{"illuminance_lx", c.illuminance_lx},
          {"area_percent", 100.0 * c.area_fraction},
          {"hours_fraction", interval(c.hours_fraction)},
          {"verdict", to_string(c.verdict)}};
}

json options_json(const AnnualOptions& o) {
  return {{"confidence", o.confidence},
          {"da_threshold_lx", o.da_threshold_lx},
          {"sda_da_fraction", o.sda_fraction},
          {"sda_nominal_percent", 100.0 * o.sda_nominal},
          {"sda_preferred_percent", 100.0 * o.sda_preferred},
          {"ase_direct_lx", o.ase_direct_lx},
          {"ase_hours", o.ase_hours},
          {"ase_maximum_percent", 100.0 * o.ase_maximum},
          {"blinds_direct_lx", o.blinds_direct_lx},
          {"blinds_area_percent", 100.0 * o.blinds_area_fraction},
          {"udi_low_lx", o.udi_low_lx},
          {"udi_high_lx", o.udi_high_lx},
          {"udi_high_alt_lx", o.udi_high_alt_lx},
          {"hour_thresholds_lx", o.hour_thresholds_lx},
          {"en17037_hours_fraction", o.en17037_hours}};
}

json cells_json(const AnnualMetrics& m) {
  const auto& cs = m.cell;
  json j;
  j["da_fraction"] = cell_arrays(
      cs, [](const auto& c) -> auto& { return c.da; });
  json sda = json::array();
  for (const AnnualCellMetrics& c : cs) sda.push_back(to_string(c.sda));
  j["sda_verdict"] = sda;
  j["udi_below_fraction"] = cell_arrays(
      cs, [](const auto& c) -> auto& { return c.udi_below; });
  j["udi_useful_fraction"] = cell_arrays(
      cs, [](const auto& c) -> auto& { return c.udi_useful; });
  j["udi_above_fraction"] = cell_arrays(
      cs, [](const auto& c) -> auto& { return c.udi_above; });
  j["udi_useful_alt_fraction"] = cell_arrays(
      cs, [](const auto& c) -> auto& { return c.udi_useful_alt; });
  j["udi_above_alt_fraction"] = cell_arrays(
      cs, [](const auto& c) -> auto& { return c.udi_above_alt; });
  json above = json::array();
  for (std::size_t t = 0; t < m.options.hour_thresholds_lx.size(); ++t)
    above.push_back({{"threshold_lx", m.options.hour_thresholds_lx[t]},
                     {"hours", cell_arrays(
                                   cs, [t](const auto& c) -> auto& { return c.hours_above[t]; })}});
  j["hours_above"] = above;
  if (m.sun_given) {
    json hours = json::array();
    for (const AnnualCellMetrics& c : cs) hours.push_back(c.ase_hours);
    j["ase_hours"] = hours;
  } else {
    j["ase_hours"] = nullptr;
  }
  return j;
}

}  // namespace

nlohmann::json annual_metrics_json(const AnnualMetrics& m) {
  json j;
  j["options"] = options_json(m.options);
  j["hours"] = m.hours;
  j["occupied_hours"] = m.occupied_hours;
  j["daylight_hours"] = m.daylight_hours;
  j["cells"] = m.cells;
  j["area_m2"] = m.area_m2;
  j["critical_values"] = {{"cell", m.z_cell}, {"grid", m.z_grid}};
  j["blinds_closed_hours"] = m.blinds_given ? json(m.blinds_closed_hours) : json(nullptr);
  j["sda_percent"] = interval(m.sda, 100.0);
  j["sda_nominal_verdict"] = to_string(m.sda_nominal);
  j["sda_preferred_verdict"] = to_string(m.sda_preferred);
  // ASE comes from the direct sun alone, traced deterministically: exact, no interval.
  if (m.sun_given) {
    j["ase_percent"] = 100.0 * m.ase;
    j["ase_verdict"] = to_string(m.ase_verdict);
  } else {
    j["ase_percent"] = nullptr;
    j["ase_verdict"] = nullptr;
  }
  j["da_fraction"] = interval(m.da);
  j["udi_below_fraction"] = interval(m.udi_below);
  j["udi_useful_fraction"] = interval(m.udi_useful);
  j["udi_above_fraction"] = interval(m.udi_above);
  j["udi_useful_alt_fraction"] = interval(m.udi_useful_alt);
  j["udi_above_alt_fraction"] = interval(m.udi_above_alt);
  json above = json::array();
  for (std::size_t t = 0; t < m.hours_above.size(); ++t)
    above.push_back(
        {{"threshold_lx", m.options.hour_thresholds_lx[t]}, {"hours", interval(m.hours_above[t])}});
  j["hours_above"] = above;
  json en = json::array();
  for (const En17037Illuminance& l : m.en17037)
    en.push_back({{"level", to_string(l.level)},
                  {"target", criterion(l.target)},
                  {"minimum", criterion(l.minimum)},
                  {"verdict", to_string(l.verdict)}});
  j["en17037"] = en;
  j["cells"] = cells_json(m);
  return j;
}

}  // namespace lightsolver
