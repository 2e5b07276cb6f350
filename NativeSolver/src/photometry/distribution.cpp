// Symmetry unfolding, the (plane, polar) grid with its exact cell fluxes, and bilinear lookup.

#include <algorithm>
#include <cmath>
#include <functional>

#include "lightsolver/angles.hpp"
#include "photometry_internal.hpp"

namespace lightsolver::photometry_detail {

namespace {

constexpr double kEps = 1e-6;  // degrees: angles closer than this are the same angle

double mod360(double a) {
  a = std::fmod(a, 360.0);
  return a < 0.0 ? a + 360.0 : a;
}

// Circular distance in degrees.
double circular_gap(double a, double b) {
  const double d = std::fmod(std::abs(a - b), 360.0);
  return std::min(d, 360.0 - d);
}

// The mirror operations whose closure turns the stored planes into the full circle. All are
// involutions, so the stored plane of a full-circle angle a is g(a) for one of them.
std::vector<std::function<double(double)>> symmetry_ops(PhotometricSymmetry s) {
  const auto id = [](double c) { return c; };
  const auto mirror_0_180 = [](double c) { return 360.0 - c; };
  const auto mirror_90_270 = [](double c) { return 180.0 - c; };
  const auto half_turn = [](double c) { return 180.0 + c; };
  switch (s) {
    case PhotometricSymmetry::BilateralC0C180:
      return {id, mirror_0_180};
    case PhotometricSymmetry::BilateralC90C270:
      return {id, mirror_90_270};
    case PhotometricSymmetry::Quadrant:
      return {id, mirror_0_180, mirror_90_270, half_turn};
    default:
      return {id};
  }
}

// Stored plane whose angle equals a (mod 360), or -1.
long find_stored(const std::vector<std::pair<double, std::size_t>>& stored, double a) {
  auto it =
      std::lower_bound(stored.begin(), stored.end(), std::make_pair(a - kEps, std::size_t{0}));
  if (it != stored.end() && circular_gap(it->first, a) < kEps) return static_cast<long>(it->second);
  // a near 0 may match a plane stored near 360, and the other way round.
  if (!stored.empty() && circular_gap(stored.front().first, a) < kEps)
    return static_cast<long>(stored.front().second);
  if (!stored.empty() && circular_gap(stored.back().first, a) < kEps)
    return static_cast<long>(stored.back().second);
  return -1;
}

void unfold_type_c(const StoredTable& t, std::vector<double>& angles,
                   std::vector<std::size_t>& rows) {
  if (t.symmetry == PhotometricSymmetry::Rotational) {
    angles = {0.0, 360.0};
    rows = {0, 0};
    return;
  }
  std::vector<std::pair<double, std::size_t>> stored;
  for (std::size_t i = 0; i < t.horizontal_deg.size(); ++i)
    stored.emplace_back(mod360(t.horizontal_deg[i]), i);
  std::sort(stored.begin(), stored.end());
  const auto ops = symmetry_ops(t.symmetry);
  std::vector<double> full;
  for (const auto& [a, row] : stored)
    for (const auto& g : ops) full.push_back(mod360(g(a)));
  std::sort(full.begin(), full.end());
  for (double a : full)
    if (angles.empty() || a - angles.back() > kEps) angles.push_back(a);
  if (angles.size() > 1 && 360.0 - angles.back() < kEps) angles.pop_back();  // 360 == 0
  for (double a : angles) {
    for (const auto& g : ops) {
      const long row = find_stored(stored, mod360(g(a)));
      if (row >= 0) {
        rows.push_back(static_cast<std::size_t>(row));
        break;
      }
    }
  }
  // Close the circle: C360 repeats C0 (a file's own C360 plane is kept if it has one).
  const long last = find_stored(stored, 360.0 - kEps / 2);
  angles.push_back(360.0);
  const bool has_own_360 =
      !t.horizontal_deg.empty() && std::abs(t.horizontal_deg.back() - 360.0) < kEps;
  rows.push_back(has_own_360 && last >= 0 ? t.horizontal_deg.size() - 1 : rows.front());
}

void unfold_type_ab(const StoredTable& t, std::vector<double>& angles,
                    std::vector<std::size_t>& rows) {
  const std::size_t n = t.horizontal_deg.size();
  if (t.symmetry == PhotometricSymmetry::LateralAB) {
    for (std::size_t i = n; i-- > 1;) {  // -h for the stored h > 0, reversed
      angles.push_back(-t.horizontal_deg[i]);
      rows.push_back(i);
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    angles.push_back(t.horizontal_deg[i]);
    rows.push_back(i);
  }
}

// Exact flux of a bilinear patch: integral over the cell of I(p, t) sin t dt dp, with the
// polar weights w0 = int (1 - u/D) sin(a + u) du and w1 = int (u/D) sin(a + u) du over [0, D].
double cell_flux(double p0, double p1, double t0, double t1, double i00, double i10, double i01,
                 double i11) {
  const double dp = (p1 - p0) * kDeg, a = t0 * kDeg, d = (t1 - t0) * kDeg;
  const double s0 = 2.0 * std::sin(a + d / 2) * std::sin(d / 2);  // cos a - cos(a + d)
  const double half = std::sin(d / 2);
  const double u = std::sin(a) * (d * std::sin(d) - 2.0 * half * half) +
                   std::cos(a) * (std::sin(d) - d * std::cos(d));  // int u sin(a + u) du
  const double w1 = u / d, w0 = s0 - w1;
  return dp * (0.5 * (i00 + i10) * w0 + 0.5 * (i01 + i11) * w1);
}

double max_sin(double t0, double t1) {
  if (t0 <= 90.0 && t1 >= 90.0) return 1.0;
  return std::max(std::sin(t0 * kDeg), std::sin(t1 * kDeg));
}

// Interval i with nodes[i] <= x <= nodes[i+1] and the fraction within it; false outside.
bool locate(const std::vector<double>& nodes, double x, std::size_t& i, double& f) {
  if (nodes.size() < 2 || x < nodes.front() - kEps || x > nodes.back() + kEps) return false;
  const auto it = std::upper_bound(nodes.begin(), nodes.end(), x);
  i = static_cast<std::size_t>(std::clamp<std::ptrdiff_t>(
      it - nodes.begin() - 1, 0, static_cast<std::ptrdiff_t>(nodes.size()) - 2));
  f = std::clamp((x - nodes[i]) / (nodes[i + 1] - nodes[i]), 0.0, 1.0);
  return true;
}

void fill_grid(const PhotometricData& d, SamplerTables& t) {
  const std::size_t nh = d.horizontal_angles_deg.size(), nv = d.vertical_angles_deg.size();
  if (d.type == PhotometricType::B) {  // plane angle V, polar angle H + 90: transpose
    t.plane_deg = d.vertical_angles_deg;
    for (double h : d.horizontal_angles_deg) t.polar_deg.push_back(h + 90.0);
    t.candela.resize(nh * nv);
    for (std::size_t h = 0; h < nh; ++h)
      for (std::size_t v = 0; v < nv; ++v) t.candela[v * nh + h] = d.candela_at(h, v);
    t.pole = {0, -1, 0}, t.zero = {0, 0, -1}, t.ninety = {1, 0, 0};
    return;
  }
  t.plane_deg = d.horizontal_angles_deg;
  t.candela = d.candela;
  if (d.type == PhotometricType::A) {  // plane angle H, polar angle V + 90
    for (double v : d.vertical_angles_deg) t.polar_deg.push_back(v + 90.0);
    t.pole = {-1, 0, 0}, t.zero = {0, 0, -1}, t.ninety = {0, 1, 0};
  } else {
    t.polar_deg = d.vertical_angles_deg;
    t.periodic = true;
    t.pole = {0, 0, -1}, t.zero = {1, 0, 0}, t.ninety = {0, 1, 0};
  }
}

}  // namespace

void unfold(const StoredTable& t, PhotometricData& data) {
  std::vector<double> angles;
  std::vector<std::size_t> rows;
  if (t.type == PhotometricType::C) {
    unfold_type_c(t, angles, rows);
  } else {
    unfold_type_ab(t, angles, rows);
  }
  const std::size_t nv = t.vertical_deg.size();
  data.vertical_angles_deg = t.vertical_deg;
  data.horizontal_angles_deg = angles;
  data.candela.clear();
  data.candela.reserve(rows.size() * nv);
  for (std::size_t row : rows)
    data.candela.insert(data.candela.end(),
                        t.candela.begin() + static_cast<std::ptrdiff_t>(row * nv),
                        t.candela.begin() + static_cast<std::ptrdiff_t>((row + 1) * nv));
}

SamplerTables make_tables(const PhotometricData& d) {
  SamplerTables t;
  fill_grid(d, t);
  const std::size_t np = t.plane_deg.size(), nt = t.polar_deg.size();
  if (np < 2 || nt < 2 || t.candela.size() != np * nt) return t;  // nothing to sample
  const auto at = [&](std::size_t i, std::size_t j) { return t.candela[i * nt + j]; };
  double sum = 0.0;
  t.cell_cdf.reserve((np - 1) * (nt - 1));
  t.cell_bound.reserve((np - 1) * (nt - 1));
  for (std::size_t i = 0; i + 1 < np; ++i) {
    for (std::size_t j = 0; j + 1 < nt; ++j) {
      const double i00 = at(i, j), i10 = at(i + 1, j), i01 = at(i, j + 1), i11 = at(i + 1, j + 1);
      sum += cell_flux(t.plane_deg[i], t.plane_deg[i + 1], t.polar_deg[j], t.polar_deg[j + 1], i00,
                       i10, i01, i11);
      t.cell_cdf.push_back(sum);
      // Slightly inflated so rounding never puts I sin t above the bound.
      t.cell_bound.push_back(std::max({i00, i10, i01, i11}) *
                             max_sin(t.polar_deg[j], t.polar_deg[j + 1]) * (1.0 + 1e-12));
    }
  }
  return t;
}

double eval_angles(const SamplerTables& t, double plane_deg, double polar_deg) {
  if (t.periodic) plane_deg = mod360(plane_deg);
  std::size_t i = 0, j = 0;
  double s = 0.0, u = 0.0;
  if (!locate(t.plane_deg, plane_deg, i, s) || !locate(t.polar_deg, polar_deg, j, u)) return 0.0;
  const std::size_t nt = t.polar_deg.size();
  const double i00 = t.candela[i * nt + j], i10 = t.candela[(i + 1) * nt + j];
  const double i01 = t.candela[i * nt + j + 1], i11 = t.candela[(i + 1) * nt + j + 1];
  return (1 - s) * (1 - u) * i00 + s * (1 - u) * i10 + (1 - s) * u * i01 + s * u * i11;
}

double eval_direction(const SamplerTables& t, const glm::dvec3& d) {
  const double len = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
  if (!(len > 0.0) || !std::isfinite(len)) return 0.0;
  const auto dot = [&](const glm::dvec3& a) { return (a.x * d.x + a.y * d.y + a.z * d.z) / len; };
  const double polar = std::acos(std::clamp(dot(t.pole), -1.0, 1.0)) / kDeg;
  const double plane = std::atan2(dot(t.ninety), dot(t.zero)) / kDeg;
  return eval_angles(t, plane, polar);
}

glm::dvec3 direction_of(const SamplerTables& t, double plane_deg, double polar_deg) {
  const double p = plane_deg * kDeg, a = polar_deg * kDeg;
  return std::cos(a) * t.pole + std::sin(a) * (std::cos(p) * t.zero + std::sin(p) * t.ninety);
}

}  // namespace lightsolver::photometry_detail
