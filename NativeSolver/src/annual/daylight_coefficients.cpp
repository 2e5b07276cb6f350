// Tracing daylight coefficients (lightsolver/daylight_coefficients.hpp): the patch and sun groups
// of coefficient_scene() in one run, photons shared by each group's importance over the year,
// and every group's estimate per grid cell kept as float32 rows.
#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <optional>
#include <string>
#include <unordered_map>

#include "lightsolver/daylight_coefficients.hpp"
#include "lightsolver/error.hpp"
#include "lightsolver/simulation.hpp"
#include "lightsolver/statistics.hpp"

namespace lightsolver {
namespace {

// An hour's scale: its global horizontal illuminance (the sky's diffuse plus the sun's beam on
// the horizontal). Hours are weighed relative to it, so a dim hour counts as much as a bright one.
double global_lx(const SkyMatrix& y, int h) {
  const double alt = y.sun_altitude_deg[h] * 3.14159265358979323846 / 180.0;
  return y.diffuse_horizontal_lx[h] + y.sun_direct_normal_lx[h] * std::max(0.0, std::sin(alt));
}

// Each patch's luminance per hour is sky[h][p] / Ω_p; its root mean square over the sky hours
// is the luminance it is traced at (so its hourly weights have mean square 1).
std::vector<double> rms_luminance(const SkyMatrix& y, const SkyPatches& patches) {
  std::vector<double> sum(y.patch_count, 0.0);
  int n = 0;
  for (int h = 0; h < y.hours; ++h) {
    if (y.status[h] != 2) continue;
    ++n;
    const float* row = &y.sky[static_cast<std::size_t>(h) * y.patch_count];
    for (int p = 0; p < y.patch_count; ++p) {
      const double l = row[p] / patches.patch(p).solid_angle_sr;
      sum[p] += l * l;
    }
  }
  for (double& v : sum) v = n > 0 ? std::sqrt(v / n) : 0.0;
  return sum;
}

// Photon weights: a group's flux × the root sum of squares of its hourly weights relative to the
// hour's global illuminance (the share that minimises Σ_h Var(E_h) / G_h² for equal per-photon
// variance).
std::vector<double> share_weights(const Simulation& sim, const SkyMatrix& y,
                                  const std::vector<double>& luminance,
                                  const SkyPatches& patches, const std::vector<int>& sun_hours) {
  const std::vector<LuminaireGroup> groups = sim.groups();
  std::vector<double> w(groups.size(), 0.0);
  for (int p = 0; p < y.patch_count; ++p) {
    if (!(luminance[p] > 0.0)) continue;
    double ss = 0.0;
    for (int h = 0; h < y.hours; ++h) {
      if (y.status[h] != 2) continue;
      const double f = y.sky[static_cast<std::size_t>(h) * y.patch_count + p] /
                       (patches.patch(p).solid_angle_sr * luminance[p] * global_lx(y, h));
      ss += f * f;
    }
    w[p] = groups[p].flux_lm * std::sqrt(ss);
  }
  for (std::size_t k = 0; k < sun_hours.size(); ++k) {
    w[y.patch_count + k] = groups[y.patch_count + k].flux_lm / global_lx(y, sun_hours[k]);
  }
  return w;
}

CoefficientGrid grid_of(const Target& t) {
  CoefficientGrid g;
  g.name = t.name;
  g.nu = t.nu;
  g.nv = t.nv;
  const glm::dvec3 n = glm::cross(t.edge1, t.edge2);
  g.normal = glm::normalize(n);
  const double area = glm::length(n) / (double(t.nu) * t.nv);
  for (std::uint32_t iv = 0; iv < t.nv; ++iv) {
    for (std::uint32_t iu = 0; iu < t.nu; ++iu) {
      g.cell_area_m2.push_back(area);
      g.cell_centre.push_back(t.corner + (iu + 0.5) / t.nu * t.edge1 + (iv + 0.5) / t.nv * t.edge2);
    }
  }
  return g;
}

// Every group's estimate of every cell at z, from the run's per-group tallies.
void fill_grid(CoefficientGrid& g, const TargetResult& tr, const Results& r, double z,
               const std::unordered_map<std::string, std::size_t>& group_row) {
  const std::size_t cells = g.cell_area_m2.size(), rows = r.groups.size();
  g.mean.assign(rows * cells, 0.0f);
  g.below.assign(rows * cells, 0.0f);
  g.above.assign(rows * cells, 0.0f);
  for (const Contribution& c : tr.contributions) {
    const std::size_t row = group_row.at(c.group);
    const GroupResult& gr = r.groups[row];
    if (gr.photons == 0 || !(gr.flux_lm > 0.0)) continue;  // no light: exactly zero
    for (std::size_t k = 0; k < cells; ++k) {
      const Estimate e =
          make_estimate_z(c.tallies.at(1 + k), gr.photons, gr.flux_lm / g.cell_area_m2[k], z);
      const std::size_t at = row * cells + k;
      g.mean[at] = static_cast<float>(e.mean);
      // Rounded outward: float must not narrow an interval.
      g.below[at] = std::nextafter(static_cast<float>(e.mean - e.ci_low), 1e30f);
      g.above[at] = std::nextafter(static_cast<float>(e.ci_high - e.mean), 1e30f);
    }
  }
}

}  // namespace

std::size_t DaylightCoefficients::bytes() const {
  std::size_t b = 0;
  for (const auto& g : grids) b += (g.mean.size() + g.below.size() + g.above.size()) * sizeof(float);
  return b;
}

struct CoefficientTracer::State {
  Scene scene;  // the traced scene: patches and suns
  DaylightCoefficients base;
  std::optional<Simulation> sim;
  std::uint64_t traced = 0;
  std::uint64_t seed = 1;
  DaylightCoefficientOptions options;
};

CoefficientTracer::CoefficientTracer(const Scene& scene, const SkyMatrix& year,
                                     const DaylightCoefficientOptions& o)
    : state_(std::make_unique<State>()) {
  State& st = *state_;
  st.options = o;
  st.scene = coefficient_scene(scene, year, o);
  st.seed = o.seed.value_or(scene.settings.seed);
  const SkyPatches patches(o.mf, o.north_deg);
  DaylightCoefficients& dc = st.base;
  dc.mf = o.mf;
  dc.north_deg = o.north_deg;
  dc.patches = year.patch_count;
  dc.patch_luminance = rms_luminance(year, patches);
  for (int p = 0; p < year.patch_count; ++p) {
    st.scene.luminaires[p].sky.zenith_luminance_cd_m2 = dc.patch_luminance[p];
  }
  for (std::size_t k = year.patch_count; k < st.scene.luminaires.size(); ++k) {
    dc.sun_hours.push_back(std::stoi(st.scene.luminaires[k].name.substr(9)));  // "sun hour N"
  }
  st.sim.emplace(st.scene, Simulation::Options{o.backend, o.threads, {}});
  st.sim->fix_photon_shares(share_weights(*st.sim, year, dc.patch_luminance, patches, dc.sun_hours));
}

CoefficientTracer::~CoefficientTracer() = default;

DaylightCoefficients CoefficientTracer::trace(std::uint64_t photons, double z) {
  State& st = *state_;
  if (!(z > 0.0) || !std::isfinite(z)) {
    throw InputError(st.scene.source_file, "z", "the intervals' critical value must be > 0");
  }
  SolveOptions so;
  so.photons = std::max(photons, st.traced);
  so.seed = st.seed;
  so.contributions = true;
  so.threads = st.options.threads;
  so.backend = st.options.backend;
  DaylightCoefficients dc = st.base;
  dc.z = z;
  dc.trace = st.traced == 0 ? st.sim->run(so) : st.sim->refine(so);
  st.traced = dc.trace.photons;
  std::unordered_map<std::string, std::size_t> group_row;
  std::size_t unlit = 0;
  for (std::size_t g = 0; g < dc.trace.groups.size(); ++g) {
    group_row[dc.trace.groups[g].name] = g;
    if (dc.trace.groups[g].flux_lm > 0.0 && dc.trace.groups[g].photons == 0) ++unlit;
  }
  if (unlit > 0) {
    throw InputError(st.scene.source_file, "photons",
                     std::to_string(unlit) + " of the " + std::to_string(dc.trace.groups.size()) +
                         " sky patch and sun groups got no photon: trace more photons (at "
                         "least " + std::to_string(20 * dc.trace.groups.size()) + ")");
  }
  std::size_t t = 0;
  for (const Target& target : st.scene.targets) {
    CoefficientGrid g = grid_of(target);
    fill_grid(g, dc.trace.targets.at(t++), dc.trace, z, group_row);
    dc.grids.push_back(std::move(g));
  }
  return dc;
}

DaylightCoefficients trace_daylight_coefficients(const Scene& scene, const SkyMatrix& year,
                                                 const DaylightCoefficientOptions& o) {
  CoefficientTracer tracer(scene, year, o);
  return tracer.trace(o.photons, o.z);
}

}  // namespace lightsolver
