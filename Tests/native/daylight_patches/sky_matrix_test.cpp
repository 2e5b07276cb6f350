// A year of sky vectors from Chicago's TMY3 file (src/daylight/sky_matrix.cpp): conventions,
// zero rows, and the horizontal illuminance rebuilt from the sky vectors plus the sun against the
// file's own global horizontal illuminance column.
#include <gtest/gtest.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "daylight/sky_vector.hpp"
#include "lightsolver/daylight.hpp"
#include "lightsolver/error.hpp"
#include "lightsolver/sky_patches.hpp"
#include "lightsolver/weather.hpp"

namespace {

using namespace lightsolver;

const std::filesystem::path kChicago = std::filesystem::path(LIGHTSOLVER_SOURCE_DIR) /
                                       "Tests/native/sun/data/" /
                                       "USA_IL_Chicago-OHare.Intl.AP.725300_TMY3.epw";

const WeatherFile& chicago() {
  static const WeatherFile w = read_epw(kChicago);
  return w;
}

double g_seconds = 0.0;  // the default matrix' time

const SkyMatrix& chicago_mf1() {
  static const SkyMatrix m = [] {
    const auto t0 = std::chrono::steady_clock::now();
    SkyMatrix r = sky_matrix(chicago(), {});
    g_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return r;
  }();
  return m;
}

// Global horizontal illuminance of hour i rebuilt from the matrix: the patches through an
// unobstructed upward sensor's daylight coefficients (mean cos Z) plus the sun, E_n sin alt.
double rebuilt_global(const SkyMatrix& m, const SkyPatches& p, std::size_t i) {
  double e = 0.0;
  const auto n = static_cast<std::size_t>(m.patch_count);
  for (int k = 1; k < m.patch_count; ++k)
    e += m.sky[i * n + static_cast<std::size_t>(k)] * p.patch(k).mean_cos_zenith;
  return e + m.sun_direct_normal_lx[i] * m.sun_direction[i * 3 + 2];
}

struct Agreement {
  double model = 0, file = 0, file_in_dark_rows = 0, mean_abs = 0, hours = 0;
};

Agreement agreement(const SkyMatrix& m, const SkyPatches& p) {
  Agreement a;
  for (std::size_t i = 0; i < chicago().hours.size(); ++i) {
    const double file = chicago().hours[i].global_horizontal_lx.value_or(0.0);
    const double model = rebuilt_global(m, p, i);
    a.model += model;
    a.file += file;
    if (m.status[i] != 2) a.file_in_dark_rows += file;
    if (m.status[i] == 2) a.mean_abs += std::abs(model - file), a.hours += 1;
  }
  a.mean_abs /= a.hours;
  return a;
}

TEST(SkyMatrix, ChicagoYearAtMf1) {
  const SkyMatrix& m = chicago_mf1();
  const double seconds = g_seconds;
  const SkyPatches p(1);
  ASSERT_EQ(m.hours, 8760);
  ASSERT_EQ(m.patch_count, 146);
  ASSERT_EQ(m.sky.size(), 8760u * 146u);
  int count[3] = {0, 0, 0};
  for (std::size_t i = 0; i < 8760; ++i) {
    ++count[m.status[i]];
    for (int k = 0; k < 146; ++k) {
      const float x = m.sky[i * 146 + static_cast<std::size_t>(k)];
      ASSERT_TRUE(std::isfinite(x) && x >= 0.0f);
      if (m.status[i] != 2) ASSERT_EQ(x, 0.0f);
    }
    ASSERT_TRUE(std::isfinite(m.sun_direct_normal_lx[i]) && m.sun_direct_normal_lx[i] >= 0.0f);
    if (m.status[i] == 0) ASSERT_LE(m.sun_altitude_deg[i], 0.0f);
    if (m.status[i] == 2) ASSERT_GT(m.sun_direction[i * 3 + 2], 0.0f);
  }
  EXPECT_LT(m.max_quadrature_error, 1e-4);
  const Agreement a = agreement(m, p);
  std::printf(
      "[ sky matrix ] Chicago MF 1: %.1f s, %zu bytes; hours night %d, no diffuse %d, sky %d\n"
      "[ sky matrix ] annual global horizontal: rebuilt %.4e lx·h, file %.4e lx·h (%+.2f %%), "
      "file's light in zero rows %.2f %%; mean |hourly difference| %.0f lx over %g sky hours; "
      "largest quadrature error %.1e\n",
      seconds, m.bytes(), count[0], count[1], count[2], a.model, a.file,
      100 * (a.model - a.file) / a.file, 100 * a.file_in_dark_rows / a.file, a.mean_abs, a.hours,
      m.max_quadrature_error);
  // Perez' efficacies against the file's own illuminance model: measured +1.7 % (docs).
  EXPECT_LT(std::abs(a.model - a.file) / a.file, 0.03);
}

// A row of the matrix (the sky normalised by its own patches) against the Sky class' vector
// (normalised by its fine horizontal integral) for the same hour: the same to the quadrature.
TEST(SkyMatrix, RowsAreTheSkyVectorsOfTheirHours) {
  const SkyMatrix& m = chicago_mf1();
  const SkyPatches p(1);
  int checked = 0;
  for (std::size_t i = 4000; i < 4400; i += 7) {
    if (m.status[i] != 2) continue;
    const WeatherHour& h = chicago().hours[i];
    daylight::SkySpec spec;
    spec.model = daylight::SkyModel::Perez;
    const float* d = &m.sun_direction[i * 3];
    spec.sun = daylight::Direction{d[0], d[1], d[2]};
    const double n = std::sqrt(spec.sun->x * spec.sun->x + spec.sun->y * spec.sun->y +
                               spec.sun->z * spec.sun->z);
    spec.sun = daylight::Direction{spec.sun->x / n, spec.sun->y / n, spec.sun->z / n};
    spec.perez.diffuse_horizontal = *h.diffuse_horizontal_w_m2;
    spec.perez.direct_normal = *h.direct_normal_w_m2;
    spec.perez.day_of_year = 0;
    for (int mo = 1; mo < h.month; ++mo)
      spec.perez.day_of_year += (mo == 2                                     ? 28
                                 : mo == 4 || mo == 6 || mo == 9 || mo == 11 ? 30
                                                                             : 31);
    spec.perez.day_of_year += h.day;
    const daylight::SkyVector v = daylight::sky_vector(spec, p);
    double total = 0.0;
    for (double x : v.patches) total += x;
    for (std::size_t k = 0; k < 146; ++k)
      ASSERT_NEAR(m.sky[i * 146 + k], v.patches[k], 1e-4 * v.patches[k] + 1e-6 * total)
          << "hour " << i << " patch " << k;
    ASSERT_NEAR(m.sun_direct_normal_lx[i], v.sun_direct_normal_lx,
                1e-6 * v.sun_direct_normal_lx + 1e-3);
    ++checked;
  }
  EXPECT_GT(checked, 20);
}

// EPW rows describe the hour ending at their stamp: the sun is placed at its middle.
// The sun at the middle of Chicago's hour i (the row's stamp ends the hour).
SunPosition middle_of_hour(std::size_t i) {
  const WeatherLocation& l = chicago().location;
  const WeatherHour& h = chicago().hours[i];
  return sun_position({l.latitude_deg, l.longitude_deg, l.elevation_m},
                      {h.year, h.month, h.day, h.hour - 1, 30, 0.0, l.utc_offset_h});
}

TEST(SkyMatrix, SunAtTheMiddleOfTheHour) {
  const SkyMatrix& m = chicago_mf1();
  for (std::size_t i : {4000u, 4012u, 100u}) {
    EXPECT_NEAR(m.sun_altitude_deg[i], middle_of_hour(i).elevation_deg, 1e-4) << i;
  }
}

// The hours' skies are computed in parallel and the suns asked for from any thread: one thread
// and many give the same matrix to the bit, and suns asked for at once from many threads are
// those asked for one at a time (libnova caches its last nutation: without the lock, positions
// depended on what another thread had asked for).
TEST(SkyMatrix, TheSameWhateverTheThreads) {
  SkyMatrix one;
  tbb::task_arena single(1);
  single.execute([&] { one = sky_matrix(chicago(), {}); });
  const SkyMatrix& many = chicago_mf1();
  EXPECT_EQ(one.sky, many.sky);
  EXPECT_EQ(one.sun_direction, many.sun_direction);
  EXPECT_EQ(one.status, many.status);
  EXPECT_EQ(one.max_quadrature_error, many.max_quadrature_error);
  constexpr std::size_t kHours = 2000;
  std::vector<double> serial(kHours), parallel(kHours);
  for (std::size_t i = 0; i < kHours; ++i) serial[i] = middle_of_hour(i * 4).elevation_deg;
  tbb::parallel_for(std::size_t(0), kHours,
                    [&](std::size_t i) { parallel[i] = middle_of_hour(i * 4).elevation_deg; });
  EXPECT_EQ(serial, parallel);
}

TEST(SkyMatrix, RadianceSunAndIlluminanceColumnsKeepTheTotals) {
  SkyMatrixOptions o;
  o.radiance_sun = true;
  const SkyMatrix smeared = sky_matrix(chicago(), o);
  const SkyMatrix& apart = chicago_mf1();
  for (std::size_t i = 0; i < 8760; ++i) {
    ASSERT_EQ(smeared.sun_direct_normal_lx[i], 0.0f);
    double d = 0.0;
    for (std::size_t k = 0; k < 146; ++k) d += smeared.sky[i * 146 + k] - apart.sky[i * 146 + k];
    ASSERT_NEAR(d, apart.sun_direct_normal_lx[i], 1e-3 * apart.sun_direct_normal_lx[i] + 1.0);
  }
  o = {};
  o.use_illuminance = true;
  const SkyMatrix lx = sky_matrix(chicago(), o);
  const Agreement a = agreement(lx, SkyPatches(1));
  std::printf(
      "[ sky matrix ] from the illuminance columns: rebuilt %.4e, file %.4e (%+.2f %%), "
      "mean |hourly difference| %.0f lx\n",
      a.model, a.file, 100 * (a.model - a.file) / a.file, a.mean_abs);
  // The file's global illuminance is its direct and diffuse illuminance recombined: measured
  // +0.05 % (docs); the hourly differences are the sun's position (middle of the hour) and float.
  EXPECT_LT(std::abs(a.model - a.file) / a.file, 0.005);
  EXPECT_LT(a.mean_abs, 200.0);
}

TEST(SkyMatrix, MissingValuesAndBadOptionsAreNamed) {
  WeatherFile w = chicago();
  std::size_t day = 0;
  while (w.hours[day].hour != 12) ++day;
  w.hours[day].diffuse_horizontal_w_m2.reset();
  try {
    sky_matrix(w, {});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("line " + std::to_string(w.hours[day].line)),
              std::string::npos);
    EXPECT_NE(std::string(e.what()).find("Diffuse Horizontal Radiation"), std::string::npos);
  }
  SkyMatrixOptions o;
  o.mf = 0;
  EXPECT_THROW(sky_matrix(chicago(), o), InputError);
  o = {};
  o.ground_reflectance = 1.5;
  EXPECT_THROW(sky_matrix(chicago(), o), InputError);
}

}  // namespace
