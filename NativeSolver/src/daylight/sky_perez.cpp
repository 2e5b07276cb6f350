// The Perez all-weather sky: clearness and brightness (Perez et al. 1990, Eqns. 1-2), the
// luminous efficacy models (ibid., Table 4, Eqns. 7-8) and the luminance coefficients of each
// clearness bin (Perez, Seals & Michalsky 1993, Table 1 with its erratum, Solar Energy 51(5):423).
// The coefficient tables are as Radiance's gendaymtx.c (Ashdown's re-implementation of
// gendaylit) prints them; so are the choices the papers leave open: Kasten's 1966 air mass and
// gendaylit's brightness range for the luminance coefficients (PerezState::shape_delta).
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "daylight/sky_models.hpp"
#include "lightsolver/angles.hpp"

namespace lightsolver::daylight {
namespace {

constexpr double kSolarConstant_w_m2 = 1367.0;
constexpr double kSolarConstant_lx = 127500.0;  // illuminance over irradiance of sunlight

// Upper clearness edge of bins 0..6; bin 7 is epsilon >= 6.2.
constexpr std::array<double, 7> kClearnessEdges = {1.065, 1.230, 1.500, 1.950, 2.800, 4.500, 6.200};

// Perez, Seals & Michalsky 1993, Table 1: per bin a1..a4, b1..b4, c1..c4, d1..d4, e1..e4.
constexpr double kLuminanceCoeff[8][20] = {
    {1.3525, -0.2576, -0.2690, -1.4366, -0.7670, 0.0007, 1.2734, -0.1233, 2.8000,  0.6004,
     1.2375, 1.0000,  1.8734,  0.6297,  0.9738,  0.2809, 0.0356, -0.1246, -0.5718, 0.9938},
    {-1.2219, -0.7730, 1.4148,  1.1016,  -0.2054, 0.0367, -3.9128, 0.9156, 6.9750,  0.1774,
     6.4477,  -0.1239, -1.5798, -0.5081, -1.7812, 0.1080, 0.2624,  0.0672, -0.2190, -0.4285},
    {-1.1000,  -0.2515, 0.8952,  0.0156, 0.2782, -0.1812, -4.5000, 1.1766, 24.7219, -13.0812,
     -37.7000, 34.8438, -5.0000, 1.5218, 3.9229, -2.6204, -0.0156, 0.1597, 0.4199,  -0.5562},
    {-0.5484,  -0.6654, -0.2672, 0.7117, 0.7234, -0.6219, -5.6812, 2.6297,  33.3389, -18.3000,
     -62.2500, 52.0781, -3.5000, 0.0016, 1.1477, 0.1062,  0.4659,  -0.3296, -0.0876, -0.0329},
    {-0.6000,  -0.3566, -2.5000, 2.3250,  0.2937, 0.0496, -5.6812, 1.8415, 21.0000, -4.7656,
     -21.5906, 7.2492,  -3.5000, -0.1554, 1.4062, 0.3988, 0.0032,  0.0766, -0.0656, -0.1294},
    {-1.0156, -0.3670, 1.0078,  1.4051,  0.2875,  -0.5328, -3.8500, 3.3750, 14.0000, -0.9999,
     -7.1406, 7.5469,  -3.4000, -0.1078, -1.0750, 1.5702,  -0.0672, 0.4016, 0.3017,  -0.4844},
    {-1.0000, 0.0211,  0.5025,  -0.5119, -0.3000, 0.1922, 0.7023, -1.6317, 19.0000, -5.0000,
     1.2438,  -1.9094, -4.0000, 0.0250,  0.3844,  0.2656, 1.0468, -0.3788, -2.4517, 1.4656},
    {-1.0500,  0.0289,  0.4260,  0.3590, -0.3250, 0.1156, 0.7781, 0.0025,  31.0625, -14.5000,
     -46.1148, 55.3750, -7.2312, 0.4050, 13.3500, 0.6234, 1.5000, -0.6426, 1.8564,  0.5636},
};

// Perez et al. 1990, Table 4: diffuse (Eqn. 7) and direct (Eqn. 8) efficacy, a b c d per bin.
constexpr double kDiffuseEfficacy[8][4] = {
    {97.24, -0.46, 12.00, -8.91},   {107.22, 1.15, 0.59, -3.95},    {104.97, 2.96, -5.53, -8.77},
    {102.39, 5.59, -13.95, -13.90}, {100.71, 5.94, -22.75, -23.74}, {106.42, 3.83, -36.15, -28.83},
    {141.88, 1.90, -53.24, -14.03}, {152.23, 0.35, -45.27, -7.98}};
constexpr double kDirectEfficacy[8][4] = {
    {57.20, -4.55, -2.98, 117.12}, {98.99, -3.46, -1.21, 12.38},  {109.83, -4.90, -1.71, -8.81},
    {110.34, -5.84, -1.99, -4.56}, {106.36, -3.97, -1.75, -6.16}, {107.19, -1.25, -1.51, -26.73},
    {105.75, 0.77, -1.26, -34.44}, {101.18, 1.58, -1.10, -8.29}};

int clearness_bin(double epsilon) {
  int bin = 0;
  while (bin < 7 && epsilon >= kClearnessEdges[bin]) ++bin;
  return bin;
}

// Kasten 1966 relative optical air mass.
double air_mass(double zenith) {
  const double deg = zenith * 180.0 / kPi;
  return 1.0 / (std::cos(zenith) + 0.15 * std::pow(93.885 - deg, -1.253));
}

// Extraterrestrial irradiance over the solar constant (Spencer's series, as gendaymtx).
double eccentricity(int day_of_year) {
  const double g = 2.0 * kPi * (day_of_year - 1) / 365.0;
  return 1.00011 + 0.034221 * std::cos(g) + 0.00128 * std::sin(g) + 0.000719 * std::cos(2 * g) +
         0.000077 * std::sin(2 * g);
}

struct Conditions {
  double zenith, air_mass, extraterrestrial, water_cm;
};

// Clearness, brightness and bin from irradiances (W/m²).
void classify(const Conditions& k, double dhi, double dni, PerezState& s) {
  const double z3 = 1.041 * k.zenith * k.zenith * k.zenith;
  s.epsilon = ((dhi + dni) / dhi + z3) / (1.0 + z3);
  s.delta = dhi * k.air_mass / k.extraterrestrial;
  s.bin = clearness_bin(s.epsilon);
  const double* kd = kDiffuseEfficacy[s.bin];
  const double* kb = kDirectEfficacy[s.bin];
  s.diffuse_efficacy_lm_w =
      kd[0] + kd[1] * k.water_cm + kd[2] * std::cos(k.zenith) + kd[3] * std::log(s.delta);
  s.direct_efficacy_lm_w = std::max(
      0.0, kb[0] + kb[1] * k.water_cm + kb[2] * std::exp(5.73 * k.zenith - 5.0) + kb[3] * s.delta);
}

void check_input(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

// gendaylit's range for the luminance coefficients' brightness.
double shape_brightness(double epsilon, double delta) {
  delta = std::clamp(delta, 0.01, 0.6);
  if (epsilon > 1.065 && epsilon < 2.8) delta = std::max(delta, 0.2);
  return delta;
}

PerezState perez_inputs(const PerezInput& in, double sun_zenith_rad) {
  check_input(std::isfinite(in.diffuse_horizontal) && in.diffuse_horizontal > 0.0,
              "perez.diffuse_horizontal: must be a finite value > 0");
  check_input(std::isfinite(in.direct_normal) && in.direct_normal >= 0.0,
              "perez.direct_normal: must be a finite value >= 0");
  check_input(in.day_of_year >= 1 && in.day_of_year <= 366, "perez.day_of_year: must be 1 to 366");
  check_input(std::isfinite(in.dew_point_c) && in.dew_point_c > -90.0 && in.dew_point_c < 60.0,
              "perez.dew_point_c: must be between -90 and 60 °C");
  check_input(std::isfinite(sun_zenith_rad) && sun_zenith_rad >= 0.0 && sun_zenith_rad <= kPi / 2,
              "sun: the Perez sky needs the sun at or above the horizon");
  const Conditions k{sun_zenith_rad, air_mass(sun_zenith_rad),
                     kSolarConstant_w_m2 * eccentricity(in.day_of_year),
                     std::exp(0.07 * in.dew_point_c - 0.075)};
  PerezState s;
  if (!in.illuminance) {
    classify(k, in.diffuse_horizontal, in.direct_normal, s);
    s.diffuse_horizontal_lx = in.diffuse_horizontal * s.diffuse_efficacy_lm_w;
    s.direct_normal_lx = in.direct_normal * s.direct_efficacy_lm_w;
    return s;
  }
  // Illuminance given: irradiance = illuminance / efficacy, the efficacy of the bin the
  // irradiance falls in; start from sunlight's mean efficacy and iterate to a fixed point.
  double dhi = in.diffuse_horizontal * kSolarConstant_w_m2 / kSolarConstant_lx;
  double dni = in.direct_normal * kSolarConstant_w_m2 / kSolarConstant_lx;
  for (int it = 0; it < 50; ++it) {
    classify(k, dhi, dni, s);
    const double kd = std::max(s.diffuse_efficacy_lm_w, 1.0);
    const double next_dhi = in.diffuse_horizontal / kd;
    const double next_dni =
        s.direct_efficacy_lm_w > 1.0 ? in.direct_normal / s.direct_efficacy_lm_w : dni;
    const bool settled = std::abs(next_dhi - dhi) <= 1e-12 * dhi &&
                         std::abs(next_dni - dni) <= 1e-12 * std::max(dni, 1.0);
    dhi = next_dhi;
    dni = next_dni;
    if (settled) break;
  }
  classify(k, dhi, dni, s);
  s.diffuse_horizontal_lx = in.diffuse_horizontal;  // the inputs are the illuminances
  s.direct_normal_lx = in.direct_normal;
  return s;
}

}  // namespace

PerezState perez_state(const PerezInput& in, double sun_zenith_rad) {
  PerezState s = perez_inputs(in, sun_zenith_rad);
  s.shape_delta = shape_brightness(s.epsilon, s.delta);
  return s;
}

SkyShape perez_shape(const PerezState& state, double sun_zenith_rad) {
  const double* x = kLuminanceCoeff[state.bin];
  const double z = sun_zenith_rad;
  const double delta = state.shape_delta;
  auto linear = [&](int i) { return x[i] + x[i + 1] * z + delta * (x[i + 2] + x[i + 3] * z); };
  SkyShape s;
  s.a = linear(0);
  s.b = linear(4);
  s.e = linear(16);
  s.k = 0.0;
  s.m = 0.0;
  if (state.bin == 0) {  // Perez 1993, Eqns. 7-8: c and d of the overcast bin
    s.c = std::exp(std::pow(delta * (x[8] + x[9] * z), x[10])) - x[11];
    s.d = -std::exp(delta * (x[12] + x[13] * z)) + x[14] + delta * x[15];
  } else {
    s.c = linear(8);
    s.d = linear(12);
  }
  return s;
}

}  // namespace lightsolver::daylight
