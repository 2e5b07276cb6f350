// An annual run (lightsolver/annual_run.hpp): weather → sky matrix → daylight coefficients →
// every hour of every grid → the annual metrics, and annual.json's summary of it all.
#include "lightsolver/annual_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iterator>
#include <string>

#include "annual/electric.hpp"
#include "estimate/decide.hpp"
#include "lightsolver/annual.hpp"
#include "lightsolver/error.hpp"
#include "lightsolver/statistics.hpp"
#include "lightsolver/weather.hpp"
#include "scene/provenance.hpp"

namespace lightsolver {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

std::string file_sha256(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return detail::sha256_hex(bytes);
}

nlohmann::json weather_json(const AnnualRunOptions& o, const WeatherFile& w, const SkyMatrix& y) {
  int sky_hours = 0;
  for (std::uint8_t s : y.status) sky_hours += s == 2;
  const WeatherLocation& l = w.location;
  return {{"file", o.weather.filename().string()},
          {"sha256", file_sha256(o.weather)},
          {"location", l.city},
          {"region", l.region},
          {"country", l.country},
          {"source", l.source},
          {"wmo", l.wmo},
          {"latitude_deg", l.latitude_deg},
          {"longitude_deg", l.longitude_deg},
          {"utc_offset_h", l.utc_offset_h},
          {"elevation_m", l.elevation_m},
          {"hours", y.hours},
          {"sky_hours", sky_hours},
          {"sky_from", o.sky.use_illuminance ? "illuminance" : "irradiance"}};
}

// Each hour's interval at the run's confidence, from the spreads and the direct beam's bounds.
void intervals(AnnualGrid& g, double z) {
  const HourlyIlluminance& e = g.hourly;
  g.low.resize(e.mean.size());
  g.high.resize(e.mean.size());
  const float zf = static_cast<float>(z);
  for (std::size_t i = 0; i < e.mean.size(); ++i) {
    g.low[i] = std::max(0.0f, e.mean[i] - zf * e.spread_low[i] - e.direct_below[i]);
    g.high[i] = e.mean[i] + zf * e.spread_high[i] + e.direct_above[i];
  }
}

// The metrics' grid: the direct beam's bounds folded into the spreads at z_fold, the smallest z
// they use (any larger z widens them: conservative).
HourlyGrid as_grid(HourlyIlluminance e, double z_fold) {
  HourlyGrid g;
  g.hours = e.hours;
  g.cells = e.cells;
  const float inv = static_cast<float>(1.0 / z_fold);
  for (std::size_t i = 0; i < e.mean.size(); ++i) {
    e.spread_low[i] += e.direct_below[i] * inv;
    e.spread_high[i] += e.direct_above[i] * inv;
  }
  g.mean = std::move(e.mean);
  g.spread_low = std::move(e.spread_low);
  g.spread_high = std::move(e.spread_high);
  g.cell_area_m2 = std::move(e.cell_area_m2);
  return g;
}

// The blinds-closed year: the sky's light alone (the beam stopped) times the blinds' τ.
HourlyGrid blinds_closed(const DaylightCoefficients& dc, const SkyMatrix& y, std::size_t grid,
                         double tau) {
  HourlyGrid g = as_grid(hourly_illuminance(dc, y, grid, false), 1.0);
  const float t = static_cast<float>(tau);
  for (float* v : {g.mean.data(), g.spread_low.data(), g.spread_high.data()}) {
    for (std::size_t i = 0; i < g.mean.size(); ++i) v[i] *= t;
  }
  return g;
}

// The year as the metrics take it: the weather, its skies, the occupied and daylight hours.
struct Year {
  WeatherFile weather;
  SkyMatrix sky;
  std::vector<std::uint8_t> occupied, daylight;
  std::vector<std::int32_t> month_day_hour;
  int occupied_hours = 0, daylight_hours = 0;
};

std::string schedule_text(const AnnualRunOptions& o) {
  if (!o.occupancy.empty()) return "given hour by hour";
  if (o.occupied_first == 9 && o.occupied_last == 18) {
    return "IES LM-83: 8:00-18:00 local standard time";
  }
  return std::to_string(o.occupied_first - 1) + ":00-" + std::to_string(o.occupied_last) +
         ":00 local standard time";
}

// The ground reflectance: the option, else the scene's sky's.
double ground_of(const Scene& scene, const AnnualRunOptions& o) {
  if (o.ground_reflectance) return *o.ground_reflectance;
  for (const Luminaire& l : scene.luminaires) {
    if (l.type == Luminaire::Type::Sky) return l.sky.ground_reflectance;
  }
  return o.sky.ground_reflectance;
}

Year read_year(const Scene& scene, AnnualRunOptions o) {
  Year y;
  o.sky.ground_reflectance = ground_of(scene, o);
  y.weather = read_epw(o.weather);
  y.sky = sky_matrix(y.weather, o.sky);
  std::vector<int> stamps;
  std::vector<double> diffuse;
  for (const WeatherHour& h : y.weather.hours) {
    stamps.push_back(h.hour);
    diffuse.push_back(h.diffuse_horizontal_lx.value_or(0.0));
    y.month_day_hour.insert(y.month_day_hour.end(), {h.month, h.day, h.hour});
  }
  if (o.occupancy.empty()) {
    y.occupied = lm83_occupancy(stamps, o.occupied_first, o.occupied_last);
  } else {
    if (o.occupancy.size() != y.weather.hours.size()) {
      throw InputError(o.weather.string(), "occupancy",
                       "one value per hour of the weather file is needed (" +
                           std::to_string(y.weather.hours.size()) + "), got " +
                           std::to_string(o.occupancy.size()));
    }
    for (std::size_t h = 0; h < o.occupancy.size(); ++h) {
      if (o.occupancy[h] > 1) {
        throw InputError("", "occupancy[" + std::to_string(h) + "]", "must be 0 or 1");
      }
    }
    y.occupied = o.occupancy;
  }
  y.daylight = en17037_daylight_hours(diffuse);
  y.occupied_hours = static_cast<int>(std::count(y.occupied.begin(), y.occupied.end(), 1));
  y.daylight_hours = static_cast<int>(std::count(y.daylight.begin(), y.daylight.end(), 1));
  return y;
}

// Every grid's hours and metrics from one set of coefficients, at `confidence`.
struct GridYears {
  std::vector<AnnualGrid> grids;
  std::vector<AnnualMetrics> metrics;
};

GridYears grid_years(const DaylightCoefficients& dc, const Year& y, const AnnualRunOptions& o,
                     double confidence) {
  AnnualOptions mo;
  mo.confidence = confidence;
  const double z = z_for_confidence(confidence);  // below every level the metrics use
  GridYears out;
  for (std::size_t g = 0; g < dc.grids.size(); ++g) {
    AnnualGrid ag;
    ag.name = dc.grids[g].name;
    ag.hourly = hourly_illuminance(dc, y.sky, g);
    intervals(ag, z);
    ag.direct_sun = dc.grids[g].direct_centre;
    const HourlyGrid closed = o.blinds_transmittance && !ag.direct_sun.empty()
                                  ? blinds_closed(dc, y.sky, g, *o.blinds_transmittance)
                                  : HourlyGrid{};
    out.metrics.push_back(annual_metrics(as_grid(ag.hourly, z), y.occupied, y.daylight,
                                         ag.direct_sun, mo, closed.hours > 0 ? &closed : nullptr));
    out.grids.push_back(std::move(ag));
  }
  return out;
}

bool decided(const std::vector<AnnualMetrics>& ms) {
  for (const AnnualMetrics& m : ms) {
    if (m.sda_nominal == VerdictKind::Undecided || m.sda_preferred == VerdictKind::Undecided)
      return false;
    for (const En17037Illuminance& e : m.en17037) {
      if (e.verdict == VerdictKind::Undecided) return false;
    }
  }
  return true;
}

int largest_grid(const Scene& scene) {
  int cells = 1;
  for (const Target& t : scene.targets) {
    if (t.type == Target::Type::Grid) cells = std::max<int>(cells, int(t.nu * t.nv));
  }
  return cells;
}

void check_options(const Scene& scene, const AnnualRunOptions& o) {
  const std::string& f = scene.source_file;
  if (!(o.confidence > 0.0 && o.confidence < 1.0)) {
    throw InputError(f, "confidence", "must be between 0 and 1 (exclusive)");
  }
  if (o.blinds_transmittance &&
      !(*o.blinds_transmittance > 0.0 && *o.blinds_transmittance <= 1.0)) {
    throw InputError(f, "blinds_transmittance", "must be more than 0 and at most 1");
  }
  if (o.max_photons && *o.max_photons < o.photons) {
    throw InputError(f, "max_photons",
                     "must be at least photons (" + std::to_string(o.photons) + ")");
  }
}

}  // namespace

AnnualResult run_annual(const Scene& scene_in, const AnnualRunOptions& o) {
  check_options(scene_in, o);
  const auto t0 = Clock::now();
  Scene scene = scene_in;
  validate(scene);
  const Year y = read_year(scene, o);
  const double t_sky = since(t0);
  DaylightCoefficientOptions co;
  co.mf = o.sky.mf;
  co.north_deg = o.sky.north_deg;
  co.photons = o.photons;
  co.seed = o.seed;
  co.backend = o.backend;
  co.threads = o.threads;
  const int cells = largest_grid(scene);
  auto strictest = [&](double confidence) {
    AnnualOptions mo;
    mo.confidence = confidence;
    return annual_strictest_z(mo, y.occupied_hours, y.daylight_hours, cells);
  };
  const auto t1 = Clock::now();
  CoefficientTracer tracer(scene, y.sky, co);
  const std::uint64_t budget = o.max_photons.value_or(16 * o.photons);
  int looks = 0;
  std::string stop = "photons";
  DaylightCoefficients dc;
  for (std::uint64_t n = o.photons;; n = std::min(budget, 2 * n)) {
    ++looks;
    const double c = o.decide ? detail::look_confidence(o.confidence, looks) : o.confidence;
    dc = tracer.trace(n, strictest(std::min(c, o.confidence)), o.progress, o.processes);
    if (dc.trace.stop_reason == "cancelled") {
      stop = "cancelled";
      break;
    }
    if (!o.decide) break;
    if (decided(grid_years(dc, y, o, c).metrics)) {
      stop = "decided";
      break;
    }
    if (n >= budget) break;
  }
  const double t_trace = since(t1);
  const auto t2 = Clock::now();
  GridYears years = grid_years(dc, y, o, o.confidence);
  const double t_hours = since(t2);
  // The scene's electric light beside the daylight: its own trace at 1 − α/2 (the hours get the
  // other half of α: electric_year).
  const auto t3 = Clock::now();
  const std::optional<Results> electric = trace_electric(
      scene, o.photons, o.seed, o.backend, o.threads, 1.0 - (1.0 - o.confidence) / 2, o.processes);
  std::vector<const Target*> grid_targets;
  for (const Target& t : scene.targets) {
    if (t.type == Target::Type::Grid) grid_targets.push_back(&t);
  }
  const double t_electric = since(t3);
  AnnualResult r;
  r.month_day_hour = y.month_day_hour;
  nlohmann::json grids = nlohmann::json::array();
  std::size_t hourly_bytes = 0;
  for (std::size_t g = 0; g < years.grids.size(); ++g) {
    const CoefficientGrid& cg = dc.grids[g];
    double area = 0.0;
    for (double a : cg.cell_area_m2) area += a;
    nlohmann::json entry = {
        {"name", cg.name},    {"nu", cg.nu},
        {"nv", cg.nv},        {"cells", cg.cell_area_m2.size()},
        {"area_m2", area},    {"metrics", annual_metrics_json(years.metrics[g])},
        {"electric", nullptr}};
    if (electric) {
      const HourlyGrid day = as_grid(years.grids[g].hourly, z_for_confidence(o.confidence));
      entry["electric"] = electric_json(electric_year(
          *grid_targets[g], electric->targets.at(g).estimate, day, y.occupied, o.confidence));
    }
    grids.push_back(std::move(entry));
    hourly_bytes += 5 * years.grids[g].hourly.mean.size() * sizeof(float) +
                    years.grids[g].direct_sun.size() * sizeof(float);
  }
  r.grids = std::move(years.grids);
  const Results& tr = dc.trace;
  r.summary = {
      {"format", "lightsolver.annual/1"},
      {"weather", weather_json(o, y.weather, y.sky)},
      {"sky",
       {{"mf", y.sky.mf},
        {"patches", y.sky.patch_count},
        {"north_deg", o.sky.north_deg},
        {"ground_reflectance", ground_of(scene, o)},
        {"max_quadrature_error", y.sky.max_quadrature_error}}},
      {"trace",
       {{"photons", tr.photons},
        {"seed", o.seed.value_or(scene.settings.seed)},
        {"backend", tr.backend},
        {"decide", o.decide},
        {"looks", looks},
        {"stop_reason", stop},
        {"sky_patch_groups", dc.patches},
        {"direct_subdivision", co.direct_subdivision},
        {"coefficient_bytes", dc.bytes()},
        {"hourly_bytes", hourly_bytes},
        {"coefficient_z", dc.z}}},
      {"seconds",
       {{"sky_matrix", t_sky},
        {"trace", t_trace},
        {"of_which_direct_sun", dc.direct_seconds},
        {"of_which_setup", dc.setup_seconds},
        {"of_which_photons", tr.seconds},
        {"hours_and_metrics", t_hours},
        {"electric", t_electric},
        {"total", since(t0)}}},
      {"occupancy", {{"schedule", schedule_text(o)}, {"hours", y.occupied_hours}}},
      {"daylight_hours", y.daylight_hours},
      {"confidence", o.confidence},
      {"blinds_transmittance",
       o.blinds_transmittance ? nlohmann::json(*o.blinds_transmittance) : nlohmann::json()},
      {"grids", grids},
      {"warnings", nlohmann::json::array()}};
  for (const std::string& wn : tr.warnings) r.summary["warnings"].push_back(wn);
  return r;
}

}  // namespace lightsolver
