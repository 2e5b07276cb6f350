// Tracing daylight coefficients (lightsolver/daylight_coefficients.hpp): the patch groups of
// coefficient_scene() in one run, photons shared by each patch's importance over the year, every
// group's estimate per grid cell (all light and reflected light) kept as float32 rows, and the
// sun's direct beam over every cell by shadow rays (direct_sun.cpp).
#include "lightsolver/daylight_coefficients.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <glm/geometric.hpp>
#include <optional>
#include <string>
#include <unordered_map>

#include "annual/sun_parts.hpp"
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

// Each patch's luminance per hour is sky[h][p] / Ω_p; its root mean square over the sky hours is
// the luminance it is traced at (so its hourly weights have mean square 1).
std::vector<double> rms_luminance(const SkyMatrix& y, const SkyPatches& patches) {
  std::vector<double> sum(y.patch_count, 0.0);
  int n = 0;
  for (int h = 0; h < y.hours; ++h) {
    if (y.status[h] != 2) continue;
    ++n;
    const float* row = &y.sky[std::size_t(h) * y.patch_count];
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
// variance): a patch's weights are its sky entries over Ω_p L_p, a sun bin's E_n / kSunBinLx in
// its hours.
std::vector<double> share_weights(const Simulation& sim, const SkyMatrix& y,
                                  const std::vector<double>& luminance, const SkyPatches& patches,
                                  const std::vector<int>& bin_of_hour) {
  const std::vector<LuminaireGroup> groups = sim.groups();
  std::vector<double> ss(groups.size(), 0.0);
  for (int h = 0; h < y.hours; ++h) {
    if (y.status[h] != 2) continue;
    const double g = global_lx(y, h);
    const float* row = &y.sky[std::size_t(h) * y.patch_count];
    for (int p = 0; p < y.patch_count; ++p) {
      if (!(luminance[p] > 0.0)) continue;
      const double f = row[p] / (patches.patch(p).solid_angle_sr * luminance[p] * g);
      ss[p] += f * f;
    }
    if (bin_of_hour[h] >= 0) {
      const double f = y.sun_direct_normal_lx[h] / (DaylightCoefficients::kSunBinLx * g);
      ss[y.patch_count + bin_of_hour[h]] += f * f;
    }
  }
  std::vector<double> w(groups.size(), 0.0);
  for (std::size_t k = 0; k < groups.size(); ++k) w[k] = groups[k].flux_lm * std::sqrt(ss[k]);
  return w;
}

// Can any surface send light on (so that a grid gets reflected light)? Glass always counts.
bool reflects(const Scene& s) {
  for (const Mesh& m : s.meshes) {
    if (m.triangles.empty() || m.material < 0) continue;
    const Material& mat = s.materials.at(std::size_t(m.material));
    if (mat.type == Material::Type::Glass || mat.reflectance > 0.0 ||
        (mat.type == Material::Type::Glossy && mat.specular > 0.0))
      return true;
  }
  return false;
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
void fill_rows(std::vector<float>& mean, std::vector<float>& below, std::vector<float>& above,
               std::size_t cells, const TargetResult& tr, const Results& r, double z,
               const std::vector<double>& cell_area_m2,
               const std::unordered_map<std::string, std::size_t>& group_row) {
  const std::size_t rows = r.groups.size();
  mean.assign(rows * cells, 0.0f);
  below.assign(rows * cells, 0.0f);
  above.assign(rows * cells, 0.0f);
  for (const Contribution& c : tr.contributions) {
    const std::size_t row = group_row.at(c.group);
    const GroupResult& gr = r.groups[row];
    if (gr.photons == 0 || !(gr.flux_lm > 0.0)) continue;  // no light: exactly zero
    for (std::size_t k = 0; k < cells; ++k) {
      const Estimate e =
          make_estimate_z(c.tallies.at(1 + k), gr.photons, gr.flux_lm / cell_area_m2[k], z);
      const std::size_t at = row * cells + k;
      mean[at] = static_cast<float>(e.mean);
      // Rounded outward: float must not narrow an interval.
      below[at] = std::nextafter(static_cast<float>(e.mean - e.ci_low), 1e30f);
      above[at] = std::nextafter(static_cast<float>(e.ci_high - e.mean), 1e30f);
    }
  }
}

}  // namespace

std::size_t DaylightCoefficients::bytes() const {
  std::size_t b = 0;
  for (const auto& g : grids) {
    for (const auto* v :
         {&g.mean, &g.below, &g.above, &g.reflected_mean, &g.reflected_below, &g.reflected_above,
          &g.direct, &g.direct_low, &g.direct_high, &g.direct_centre}) {
      b += v->size() * sizeof(float);
    }
  }
  return b;
}

struct CoefficientTracer::State {
  Scene scene;  // the traced scene: patches, grids and their reflected twins
  DaylightCoefficients base;
  std::optional<Simulation> sim;
  std::uint64_t traced = 0;
  std::uint64_t seed = 1;
  DaylightCoefficientOptions options;
};

CoefficientTracer::CoefficientTracer(const Scene& scene_in, const SkyMatrix& year,
                                     const DaylightCoefficientOptions& o)
    : state_(std::make_unique<State>()) {
  if (o.direct_subdivision < 1 || o.direct_subdivision > 64) {
    throw InputError(scene_in.source_file, "direct_subdivision", "must be 1 … 64");
  }
  Scene scene = scene_in;
  validate(scene);
  State& st = *state_;
  st.options = o;
  st.seed = o.seed.value_or(scene.settings.seed);
  const SkyPatches patches(o.mf, o.north_deg);
  if (o.sun_mf < 1 || o.sun_mf > 64) {
    throw InputError(scene_in.source_file, "sun_mf", "must be 1 … 64");
  }
  // Nothing reflects: the sun's reflected light is exactly zero, no sun bin is traced (the beam
  // itself is the shadow rays').
  SunBins bins = reflects(scene) ? sun_bins(year, o.sun_mf, o.north_deg)
                                 : SunBins{{}, std::vector<int>(year.hours, -1)};
  DaylightCoefficients& dc = st.base;
  dc.mf = o.mf;
  dc.north_deg = o.north_deg;
  dc.patches = year.patch_count;
  dc.patch_luminance = rms_luminance(year, patches);
  dc.sun_bins = std::move(bins.direction);
  dc.sun_bin_of_hour = std::move(bins.of_hour);
  st.scene = coefficient_scene(scene, year, o, dc.sun_bins);
  for (int p = 0; p < year.patch_count; ++p) {
    st.scene.luminaires[p].sky.zenith_luminance_cd_m2 = dc.patch_luminance[p];
  }
  const auto t0 = std::chrono::steady_clock::now();
  for (std::size_t t = 0; t < st.scene.targets.size(); t += 2) {
    dc.grids.push_back(grid_of(st.scene.targets[t]));
    direct_sun_cells(scene, st.scene.targets[t], year, o.direct_subdivision, dc.grids.back());
  }
  const auto t1 = std::chrono::steady_clock::now();
  dc.direct_seconds = std::chrono::duration<double>(t1 - t0).count();
  st.sim.emplace(st.scene, Simulation::Options{o.backend, o.threads, {}});
  st.sim->fix_photon_shares(
      share_weights(*st.sim, year, dc.patch_luminance, patches, dc.sun_bin_of_hour));
  dc.setup_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
}

CoefficientTracer::~CoefficientTracer() = default;

DaylightCoefficients CoefficientTracer::trace(std::uint64_t photons, double z,
                                              const ProgressFn& progress,
                                              std::shared_ptr<ProcessGroup> processes) {
  State& st = *state_;
  if (!(z > 0.0) || !std::isfinite(z)) {
    throw InputError(st.scene.source_file, "z", "the intervals' critical value must be > 0");
  }
  SolveOptions so;
  so.photons = std::max(photons, st.traced);
  so.seed = st.seed;
  so.contributions = true;
  // fill_rows reads each group's photon tallies alone: every patch's and sun bin's light,
  // direct included, is in its photons (sky and sun have no next-event hook either).
  so.next_event = "off";
  so.threads = st.options.threads;
  so.backend = st.options.backend;
  so.processes = std::move(processes);
  DaylightCoefficients dc = st.base;
  dc.z = z;
  dc.trace = st.traced == 0 ? st.sim->run(so, progress) : st.sim->refine(so, progress);
  st.traced = dc.trace.photons;
  std::unordered_map<std::string, std::size_t> group_row;
  std::size_t unlit = 0;
  for (std::size_t g = 0; g < dc.trace.groups.size(); ++g) {
    group_row[dc.trace.groups[g].name] = g;
    if (dc.trace.groups[g].flux_lm > 0.0 && dc.trace.groups[g].photons == 0) ++unlit;
  }
  if (unlit > 0) {
    throw InputError(
        st.scene.source_file, "photons",
        std::to_string(unlit) + " of the " + std::to_string(dc.trace.groups.size()) +
            " sky patch and sun bin groups got no photon: trace more photons (at least " +
            std::to_string(20 * dc.trace.groups.size()) + ")");
  }
  for (std::size_t g = 0; g < dc.grids.size(); ++g) {
    CoefficientGrid& cg = dc.grids[g];
    const std::size_t cells = cg.cell_area_m2.size();
    fill_rows(cg.mean, cg.below, cg.above, cells, dc.trace.targets.at(2 * g), dc.trace, z,
              cg.cell_area_m2, group_row);
    fill_rows(cg.reflected_mean, cg.reflected_below, cg.reflected_above, cells,
              dc.trace.targets.at(2 * g + 1), dc.trace, z, cg.cell_area_m2, group_row);
  }
  return dc;
}

DaylightCoefficients trace_daylight_coefficients(const Scene& scene, const SkyMatrix& year,
                                                 const DaylightCoefficientOptions& o) {
  CoefficientTracer tracer(scene, year, o);
  return tracer.trace(o.photons, o.z);
}

}  // namespace lightsolver
