// The standard UGR table of a luminaire (CIE 190:2010 tabular method): 19 rooms, five
// reflectance combinations, crosswise and endwise, background luminance from the array's direct
// flux on floor, walls and ceiling and the room's interreflection (CIE 190 eq. 7-12).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <glm/geometric.hpp>
#include <sstream>

#include "lightsolver/angles.hpp"
#include "lightsolver/glare.hpp"

namespace lightsolver {
namespace {

constexpr int kPhiSteps = 720;    // world azimuth, 0.5 degree cells (midpoints)
constexpr int kGammaSteps = 360;  // 0.25 degree steps from nadir to horizontal

// The 19 rooms of CIE 190 data sheets: X across the line of sight, Y along it, in H.
constexpr std::array<std::array<double, 2>, 19> kRooms{{{2, 2},
                                                        {2, 3},
                                                        {2, 4},
                                                        {2, 6},
                                                        {2, 8},
                                                        {2, 12},
                                                        {4, 2},
                                                        {4, 3},
                                                        {4, 4},
                                                        {4, 6},
                                                        {4, 8},
                                                        {4, 12},
                                                        {8, 4},
                                                        {8, 6},
                                                        {8, 8},
                                                        {8, 12},
                                                        {12, 4},
                                                        {12, 6},
                                                        {12, 8}}};

// Form factor between two directly opposed, equal a x b rectangles a distance c apart.
double parallel_form_factor(double a, double b, double c) {
  const double x = a / c, y = b / c, x2 = x * x, y2 = y * y;
  return 2.0 / (kPi * x * y) *
         (std::log(std::sqrt((1 + x2) * (1 + y2) / (1 + x2 + y2))) +
          x * std::sqrt(1 + y2) * std::atan(x / std::sqrt(1 + y2)) +
          y * std::sqrt(1 + x2) * std::atan(y / std::sqrt(1 + x2)) - x * std::atan(x) -
          y * std::atan(y));
}

// Solves the 3x3 system m * s = b (Cramer; the matrix is diagonally dominant).
std::array<double, 3> solve3(const std::array<std::array<double, 3>, 3>& m,
                             const std::array<double, 3>& b) {
  const auto det = [](const std::array<std::array<double, 3>, 3>& a) {
    return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
           a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
           a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  };
  const double d = det(m);
  std::array<double, 3> s{};
  for (int k = 0; k < 3; ++k) {
    auto mk = m;
    for (int i = 0; i < 3; ++i) mk[i][k] = b[i];
    s[k] = det(mk) / d;
  }
  return s;
}

// Cumulative downward intensity of one luminaire orientation: g[k][j] = integral over gamma
// from 0 to j steps of I sin(gamma) dgamma along world azimuth k (cell midpoint); also the
// upward flux.
struct Cumulative {
  std::vector<double> g;  // kPhiSteps x (kGammaSteps + 1)
  double down_lm = 0.0, up_lm = 0.0;
  double at(int k, double gamma) const {  // linear in gamma (radians, 0..pi/2)
    const double s = std::clamp(gamma / (0.5 * kPi) * kGammaSteps, 0.0, double(kGammaSteps));
    const int j = std::min(static_cast<int>(s), kGammaSteps - 1);
    const double* row = &g[static_cast<std::size_t>(k) * (kGammaSteps + 1)];
    return row[j] + (s - j) * (row[j + 1] - row[j]);
  }
};

Cumulative cumulate(const PhotometricSampler& sampler, const glm::dvec3& c0, double scale) {
  const glm::dvec3 aim{0, 0, -1}, c90 = glm::cross(c0, aim);
  const auto intensity = [&](double phi, double gamma) {
    const glm::dvec3 w{std::sin(gamma) * std::cos(phi), std::sin(gamma) * std::sin(phi),
                       -std::cos(gamma)};
    return scale * sampler.intensity_cd({glm::dot(w, c0), glm::dot(w, c90), -glm::dot(w, aim)});
  };
  Cumulative c;
  c.g.assign(static_cast<std::size_t>(kPhiSteps) * (kGammaSteps + 1), 0.0);
  const double dphi = 2.0 * kPi / kPhiSteps, dg = 0.5 * kPi / kGammaSteps;
  for (int k = 0; k < kPhiSteps; ++k) {
    const double phi = (k + 0.5) * dphi;
    double* row = &c.g[static_cast<std::size_t>(k) * (kGammaSteps + 1)];
    double prev = 0.0;                        // I sin(gamma) at gamma = 0
    for (int j = 1; j <= kGammaSteps; ++j) {  // trapezoids, downward hemisphere
      const double gamma = j * dg, f = intensity(phi, gamma) * std::sin(gamma);
      row[j] = row[j - 1] + 0.5 * (prev + f) * dg;
      prev = f;
    }
    c.down_lm += row[kGammaSteps] * dphi;
    prev = 0.0;
    for (int j = 1; j <= kGammaSteps; ++j) {  // upward hemisphere, from the zenith down
      const double gamma = kPi - j * dg, f = intensity(phi, gamma) * std::sin(gamma);
      c.up_lm += 0.5 * (prev + f) * dg * dphi;
      prev = f;
    }
  }
  return c;
}

// Direct flux on the floor (reference plane, `height` below) of a luminaire at (x, y) in the
// room [-half_x, half_x] x [0, length_y]: along each azimuth, the rays that leave the room
// through a wall miss the floor.
double floor_flux_lm(const Cumulative& c, double x, double y, double half_x, double length_y,
                     double height) {
  const double dphi = 2.0 * kPi / kPhiSteps;
  double sum = 0.0;
  for (int k = 0; k < kPhiSteps; ++k) {
    const double phi = (k + 0.5) * dphi, cx = std::cos(phi), sy = std::sin(phi);
    double reach = 1e300;
    if (cx > 1e-12) reach = std::min(reach, (half_x - x) / cx);
    if (cx < -1e-12) reach = std::min(reach, (-half_x - x) / cx);
    if (sy > 1e-12) reach = std::min(reach, (length_y - y) / sy);
    if (sy < -1e-12) reach = std::min(reach, -y / sy);
    sum += c.at(k, std::atan2(reach, height));
  }
  return sum * dphi;
}

std::string fixed(double v, int decimals) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

}  // namespace

WallTransferFactors wall_transfer_factors(double x_m, double y_m, double height_m,
                                          const RoomReflectances& rho) {
  // Surfaces 0 floor, 1 walls, 2 ceiling. Incident flux Phi = direct + sum_j rho_j F_ji Phi_j.
  const double a_floor = x_m * y_m, a_walls = 2.0 * height_m * (x_m + y_m);
  const double f_fc = parallel_form_factor(x_m, y_m, height_m), f_fw = 1.0 - f_fc;
  const double f_wf = a_floor * f_fw / a_walls, f_ww = 1.0 - 2.0 * f_wf;
  const std::array<std::array<double, 3>, 3> f{{{0.0, f_fw, f_fc},  // f[i][j]: from i to j
                                                {f_wf, f_ww, f_wf},
                                                {f_fc, f_fw, 0.0}}};
  const std::array<double, 3> r{rho.floor, rho.walls, rho.ceiling};
  std::array<std::array<double, 3>, 3> m{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m[i][j] = (i == j ? 1.0 : 0.0) - r[j] * f[j][i];
  WallTransferFactors t;
  t.floor_to_walls = solve3(m, {1, 0, 0})[1];
  t.walls_to_walls = solve3(m, {0, 1, 0})[1] - 1.0;
  t.ceiling_to_walls = solve3(m, {0, 0, 1})[1];
  return t;
}

std::vector<RoomReflectances> standard_reflectances() {
  return {{0.7, 0.5, 0.2}, {0.7, 0.3, 0.2}, {0.5, 0.5, 0.2}, {0.5, 0.3, 0.2}, {0.3, 0.3, 0.2}};
}

UgrTable ugr_table(const PhotometricData& data, const UgrTableOptions& options) {
  if (data.opening_shape == OpeningShape::Point)
    throw InputError(data.source_file, "luminous opening",
                     "the file gives no luminous area; a UGR table needs one (CIE 190)");
  if (!(options.spacing_to_height > 0.0) || !(options.height_m > 0.0) ||
      !(options.flux_scale > 0.0))
    throw InputError("", "UGR table", "spacing_to_height, height_m and flux_scale must be > 0");
  auto shared_data = std::make_shared<const PhotometricData>(data);
  auto sampler = std::make_shared<const PhotometricSampler>(data);
  UgrTable table;
  table.reflectances = standard_reflectances();
  table.spacing_to_height = options.spacing_to_height;
  table.luminaire_flux_lm = sampler->integrated_flux_lm() * options.flux_scale;
  table.lamp_flux_lm = (!data.absolute_photometry && data.rated_lumens_lm > 0.0)
                           ? data.rated_lumens_lm * options.flux_scale
                           : table.luminaire_flux_lm;

  const double h = options.height_m, s = options.spacing_to_height * h;
  // Crosswise: the line of sight (+y) lies in the C0-C180 plane, C0 toward the observer
  // (CIE 117 eq. 4.5); endwise: C90 toward the observer (eq. 4.6).
  const std::array<glm::dvec3, 2> c0s{glm::dvec3{0, -1, 0}, glm::dvec3{-1, 0, 0}};
  std::array<Cumulative, 2> cum{cumulate(*sampler, c0s[0], options.flux_scale),
                                cumulate(*sampler, c0s[1], options.flux_scale)};
  GlareObserver eye{{0, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  int small = 0, large = 0, counted = 0;
  for (const auto& room : kRooms) {
    UgrTableRow row;
    row.x_h = room[0];
    row.y_h = room[1];
    const double xm = room[0] * h, ym = room[1] * h;
    const int nx = static_cast<int>(std::lround(xm / s)),
              ny = static_cast<int>(std::lround(ym / s));
    for (int o = 0; o < 2; ++o) {
      std::vector<GlareSource> sources;
      double floor_lm = 0.0;
      for (int i = 0; i < nx; ++i) {
        for (int j = 0; j < ny; ++j) {
          const double x = -0.5 * xm + (i + 0.5) * s, y = (j + 0.5) * s;
          floor_lm += floor_flux_lm(cum[o], x, y, 0.5 * xm, ym, h);
          sources.push_back(photometric_glare_source("", shared_data, sampler, {x, y, h},
                                                     {0, 0, -1}, c0s[o], options.flux_scale));
        }
      }
      const double n = static_cast<double>(nx) * ny;
      const double walls_lm = n * cum[o].down_lm - floor_lm, ceiling_lm = n * cum[o].up_lm;
      if (o == 0) row.direct_floor_fraction = floor_lm / (n * (cum[o].down_lm + cum[o].up_lm));
      const UgrResult sum = compute_ugr(eye, sources, 1.0);
      for (const auto& c : sum.contributions) {
        if (!c.counted) continue;
        ++counted;
        small += c.solid_angle_sr < 3e-4;
        large += c.solid_angle_sr > 0.1;
      }
      for (const RoomReflectances& rho : table.reflectances) {
        const WallTransferFactors t = wall_transfer_factors(xm, ym, h, rho);
        const double indirect_walls_lm = floor_lm * t.floor_to_walls + walls_lm * t.walls_to_walls +
                                         ceiling_lm * t.ceiling_to_walls;
        const double lb = indirect_walls_lm / (2.0 * h * (xm + ym)) / kPi;
        std::optional<double> ugr;
        if (sum.sum > 0.0 && lb > 0.0) ugr = 8.0 * std::log10(0.25 * sum.sum / lb);
        (o == 0 ? row.crosswise : row.endwise).push_back(ugr);
        if (o == 0) row.background_luminance_cd_m2.push_back(lb);
      }
    }
    table.rows.push_back(std::move(row));
  }
  if (small > 0)
    table.warnings.push_back(std::to_string(small) + " of " + std::to_string(counted) +
                             " luminaire positions counted subtend less than 0.0003 sr, below "
                             "CIE 117's range (small sources: CIE 147)");
  if (large > 0)
    table.warnings.push_back(std::to_string(large) + " of " + std::to_string(counted) +
                             " luminaire positions counted subtend more than 0.1 sr, above "
                             "CIE 117's range (large sources: CIE 147)");
  return table;
}

std::string format_ugr_table(const UgrTable& t) {
  std::ostringstream out;
  out << "UGR table (CIE 190:2010 tabular method), luminaire flux " << fixed(t.luminaire_flux_lm, 0)
      << " lm, lamp flux " << fixed(t.lamp_flux_lm, 0)
      << " lm (corrected values; CIE 190's 1000 lm values are "
      << fixed(8.0 * std::log10(t.lamp_flux_lm / 1000.0), 1) << " lower)\n"
      << "spacing " << fixed(t.spacing_to_height, 2)
      << " H, observer at mid-wall, eye H below the luminaires\n";
  const auto refl_line = [&](const char* label, auto member) {
    out << label;
    for (int o = 0; o < 2; ++o) {
      for (const auto& r : t.reflectances) out << "  " << fixed(r.*member, 2);
      out << (o == 0 ? "  |" : "\n");
    }
  };
  refl_line("ceiling        ", &RoomReflectances::ceiling);
  refl_line("walls          ", &RoomReflectances::walls);
  refl_line("floor          ", &RoomReflectances::floor);
  out << "room X   Y     crosswise                     |  endwise\n";
  const auto cell = [](const std::optional<double>& v) {
    std::string s = v ? fixed(*v, 1) : "-";
    return std::string(6 - std::min<std::size_t>(6, s.size()), ' ') + s;
  };
  for (const UgrTableRow& row : t.rows) {
    std::string x = fixed(row.x_h, 0) + "H", y = fixed(row.y_h, 0) + "H";
    out << "    " << x << std::string(5 - x.size(), ' ') << y << std::string(4 - y.size(), ' ');
    for (const auto& v : row.crosswise) out << cell(v);
    out << "  |";
    for (const auto& v : row.endwise) out << cell(v);
    out << "\n";
  }
  for (const std::string& w : t.warnings) out << "warning: " << w << "\n";
  return out.str();
}

}  // namespace lightsolver
