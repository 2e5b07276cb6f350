#include "estimate/next_event.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include "estimate/direct_choice.hpp"
#include "lightsolver/error.hpp"
#include "model/sampling.hpp"
#include "types/luminaire_types.hpp"

namespace lightsolver::detail {
namespace {

using glm::dvec3;

// The points' random streams: PathRng stream kStream | group, which no photon group uses
// (groups x bins are at most 2^26), path id (bin << 20) | point.
constexpr std::uint32_t kStream = 0x80000000u;
// Rays gathered before the backend traces them (8 MiB of rays).
constexpr std::size_t kBatchRays = std::size_t(1) << 18;
// A shadow ray stops this fraction short of the light's point, which sits a few ULPs off the
// surface it may be flush with (offset_ray_origin, as its photons start).
constexpr double kShortOfLight = 1e-4;

// A surface target's triangles (world, prepared coordinates) and their areas.
struct Surface {
  std::vector<dvec3> v0, e1, e2, n;
  std::vector<double> cdf;  // cumulative area fractions, last = 1
};

// Where one bin's points lie: a parallelogram (a grid cell) or the triangles of the surface
// target's meshes, by area.
struct Domain {
  std::uint32_t bin = 0;
  std::uint32_t strata = 1;  // cells: per side (s x s); surfaces: along the area's CDF
  dvec3 corner{0.0}, e1{0.0}, e2{0.0}, normal{0.0, 0.0, 1.0};
  const Surface* surface = nullptr;
  std::uint32_t stratum_count() const { return surface ? strata : strata * strata; }
};

// A point of stratum k (and its receiver normal), uniform within the stratum.
void point_in(const Domain& d, std::uint32_t k, PathRng& rng, dvec3& x, dvec3& n) {
  const double u = rng.uniform_double(), v = rng.uniform_double();
  if (!d.surface) {
    const double a = ((k % d.strata) + u) / d.strata, b = ((k / d.strata) + v) / d.strata;
    x = d.corner + a * d.e1 + b * d.e2;
    n = d.normal;
    return;
  }
  const Surface& s = *d.surface;
  const double along = (k + u) / d.strata;
  const std::size_t t = std::min<std::size_t>(
      std::upper_bound(s.cdf.begin(), s.cdf.end(), along) - s.cdf.begin(), s.cdf.size() - 1);
  const double w = rng.uniform_double(), su = std::sqrt(v);  // uniform on the triangle
  x = s.v0[t] + su * (1.0 - w) * s.e1[t] + su * w * s.e2[t];
  n = s.n[t];
}

// A surface target's meshes as one sampling domain (their current transforms applied).
Surface surface_of(const PreparedScene& s, std::uint32_t bin) {
  Surface out;
  double area = 0.0;
  for (const PreparedMesh& m : s.meshes) {
    if (m.bin != std::int32_t(bin)) continue;
    const glm::dmat4 to_world(m.transform);
    const glm::dmat3 rotate(to_world);
    for (std::size_t t = 0; t < m.normals.size(); ++t) {
      dvec3 p[3];
      for (int c = 0; c < 3; ++c) {
        const std::uint32_t i = m.indices[3 * t + c];
        const glm::dvec4 local(m.vertices[3 * i], m.vertices[3 * i + 1], m.vertices[3 * i + 2],
                               1.0);
        p[c] = dvec3(to_world * local);
      }
      const double a = 0.5 * glm::length(glm::cross(p[1] - p[0], p[2] - p[0]));
      if (!(a > 0.0)) continue;
      area += a;
      out.v0.push_back(p[0]);
      out.e1.push_back(p[1] - p[0]);
      out.e2.push_back(p[2] - p[0]);
      out.n.push_back(glm::normalize(rotate * dvec3(m.normals[t])));
      out.cdf.push_back(area);
    }
  }
  for (double& c : out.cdf) c /= area;
  if (!out.cdf.empty()) out.cdf.back() = 1.0;
  return out;
}

// A grid row's cell (iu, iv) as a parallelogram. The row keeps its edges' dual vectors; the
// edges, in the plane they span, are those duals times the inverse of their Gram matrix.
Domain cell_domain(const PreparedGrid& g, std::uint32_t iu, std::uint32_t iv) {
  const dvec3 du(g.du), dv(g.dv);
  const double a = glm::dot(du, du), b = glm::dot(du, dv), c = glm::dot(dv, dv);
  const double det = a * c - b * b;
  const dvec3 e1 = (c * du - b * dv) / det, e2 = (a * dv - b * du) / det;
  Domain d;
  d.bin = g.bin + 1 + iv * g.nu + iu;
  d.e1 = e1 / double(g.nu);
  d.e2 = e2 / double(g.nv);
  d.corner = dvec3(g.corner) + double(iu) * d.e1 + double(iv) * d.e2;
  d.normal = glm::normalize(dvec3(g.normal));
  return d;
}

// One (domain, group) set of points, two per stratum, and the rays they sent.
struct Job {
  Domain domain;
  std::uint32_t group = 0;
  std::size_t first_point = 0;
};

class Evaluator {
 public:
  Evaluator(const PreparedScene& s, Backend& backend, std::uint64_t seed,
            const std::function<bool()>& stop)
      : s_(s),
        backend_(backend),
        seed_(seed),
        stop_(stop),
        parts_(s.groups.size() * s.bins.size()) {}

  /// A stop was asked for: the parts are incomplete and must not be used.
  bool stopped() const { return stopped_; }

  void add(const Domain& d, std::uint32_t group) {
    if (stopped_) return;
    jobs_.push_back({d, group, values_.size()});
    const PreparedGroup& g = s_.groups[group];
    const std::uint32_t points = 2 * d.stratum_count();
    for (std::uint32_t p = 0; p < points; ++p) {
      PathRng rng(seed_, (std::uint64_t(d.bin) << 20) | p, kStream | group);
      dvec3 x, n;
      point_in(d, p / 2, rng, x, n);
      const vec3 origin = offset_ray_origin(vec3(x), vec3(n));
      const std::size_t point = values_.size();
      values_.push_back(0.0);
      for (const std::uint32_t l : g.luminaires) {
        const PreparedLuminaire& lum = s_.luminaires[l];
        const LightSample ls = luminaire_type(lum.type).direct(lum, x, rng);
        // The cosine at x itself: the ray's origin sits off the receiver (offset_ray_origin,
        // up to 1.5e-5 m near 0), which would bias a cosine taken from there.
        const dvec3 from_x = ls.to - x, to_light = ls.to - dvec3(origin);
        const double dist = glm::length(to_light), dist_x = glm::length(from_x);
        if (!(ls.lux > 0.0) || !(dist > 0.0) || !(dist_x > 0.0)) continue;
        const double cos_r = glm::dot(n, from_x) / dist_x;
        if (!(cos_r > 0.0)) continue;  // behind the receiver: its photons would not count
        rays_.push_back({origin, float(dist * (1.0 - kShortOfLight)), vec3(to_light / dist)});
        ray_lux_.push_back({point, ls.lux * cos_r});
      }
    }
    if (rays_.size() >= kBatchRays) flush();
  }

  std::vector<DirectPart> finish() {
    flush();
    return std::move(parts_);
  }

 private:
  void flush() {
    // Each batch of rays is a cancellation point: a stopped evaluation traces no more.
    if (stopped_ || (stop_ && stop_())) {
      stopped_ = true;
      return;
    }
    std::vector<std::uint8_t> seen;
    backend_.visible(rays_, seen);
    for (std::size_t i = 0; i < rays_.size(); ++i) {
      if (seen[i]) values_[ray_lux_[i].point] += ray_lux_[i].lux;
    }
    for (const Job& j : jobs_) finish_job(j);
    jobs_.clear();
    rays_.clear();
    ray_lux_.clear();
    values_.clear();
  }

  // Stratified mean of 2 points per stratum and its unbiased variance: sum over strata of
  // (y1 - y2)^2 / 4, over K^2.
  void finish_job(const Job& j) {
    const std::uint32_t strata = j.domain.stratum_count();
    double sum = 0.0, spread = 0.0;
    std::uint64_t lit = 0;
    for (std::uint32_t k = 0; k < strata; ++k) {
      const double y1 = values_[j.first_point + 2 * k], y2 = values_[j.first_point + 2 * k + 1];
      sum += y1 + y2;
      spread += 0.25 * (y1 - y2) * (y1 - y2);
      lit += (y1 > 0.0) + (y2 > 0.0);
    }
    DirectPart& part = parts_[j.group * s_.bins.size() + j.domain.bin];
    part.lux = sum / (2.0 * strata);
    part.variance = spread / (double(strata) * strata);
    part.lit = lit;
  }

  struct RayLux {
    std::size_t point;
    double lux;
  };
  const PreparedScene& s_;
  Backend& backend_;
  std::uint64_t seed_;
  const std::function<bool()>& stop_;
  bool stopped_ = false;
  std::vector<DirectPart> parts_;
  std::vector<Job> jobs_;
  std::vector<ShadowRay> rays_;
  std::vector<RayLux> ray_lux_;
  std::vector<double> values_;  // per point of the pending jobs: its direct illuminance
};

// The surface targets' bins, each once (a target's meshes share its bin), in mesh order;
// `shadow_rays_only`: not those given back to the photons (direct_by_photons).
std::vector<std::uint32_t> surface_bins(const PreparedScene& s, bool shadow_rays_only = false) {
  std::vector<std::uint32_t> bins;
  for (const PreparedMesh& m : s.meshes) {
    if (m.bin < 0 || m.normals.empty() || (shadow_rays_only && m.direct_by_photons)) continue;
    if (std::find(bins.begin(), bins.end(), std::uint32_t(m.bin)) == bins.end()) {
      bins.push_back(std::uint32_t(m.bin));
    }
  }
  return bins;
}

bool has_direct_targets(const PreparedScene& s) {
  const bool grids = std::any_of(s.grids.begin(), s.grids.end(),
                                 [](const PreparedGrid& g) { return !g.indirect_only; });
  return grids || !surface_bins(s).empty();
}

bool samples_directly(const PreparedScene& s, const PreparedGroup& g) {
  if (!(g.flux_lm > 0.0) || g.luminaires.empty()) return false;
  return std::all_of(g.luminaires.begin(), g.luminaires.end(), [&](std::uint32_t l) {
    return luminaire_type(s.luminaires[l].type).direct != nullptr;
  });
}

}  // namespace

void plan_next_event(PreparedScene& s, const Backend& backend, const std::string& mode) {
  for (PreparedGroup& g : s.groups) g.next_event = g.connect = false;  // connect needs it
  for (PreparedGrid& g : s.grids) g.connect_r0 = 0.0f;
  clear_direct_by_photons(s);  // "auto" may give some back once it has judged them
  s.next_event_targets.clear();
  s.connect_off = "needs next-event estimation (next_event)";
  s.direct.clear();
  const bool forced = mode == "on";
  const auto off = [&](const std::string& why) {
    s.next_event_off = why;
    if (forced) throw InputError("", "next_event", "\"on\", but " + why);
  };
  if (mode == "off") {
    s.next_event_off = "off by the next_event setting";
    return;
  }
  if (!has_direct_targets(s)) return off("no grid or surface target");
  if (!backend.traces_shadow_rays()) {
    return off("the " + backend.name() + " backend traces no shadow rays");
  }
  bool any = false;
  for (PreparedGroup& g : s.groups) {
    g.next_event = samples_directly(s, g);
    any = any || g.next_event;
  }
  if (!any) return off("no lit luminaire group of types with direct sampling (sky, sun)");
  s.next_event_off.clear();
}

std::uint64_t direct_ray_count(const PreparedScene& s, std::uint32_t strata_scale) {
  std::uint64_t luminaires = 0;
  for (const PreparedGroup& g : s.groups) luminaires += g.next_event ? g.luminaires.size() : 0;
  std::uint64_t points = 0;
  const std::uint64_t side = kCellStrataSide * strata_scale;
  for (const PreparedGrid& grid : s.grids) {
    if (!grid.indirect_only && !grid.direct_by_photons) {
      points += std::uint64_t(grid.nu) * grid.nv * 2 * side * side;
    }
  }
  points += surface_bins(s, true).size() * 2 * std::uint64_t(kSurfaceStrata) * strata_scale *
            strata_scale;
  return points * luminaires;
}

std::vector<DirectPart> direct_parts(const PreparedScene& s, Backend& backend, std::uint64_t seed,
                                     std::uint32_t strata_scale) {
  return *direct_parts_unless(s, backend, seed, strata_scale, {});
}

std::optional<std::vector<DirectPart>> direct_parts_unless(const PreparedScene& s, Backend& backend,
                                                           std::uint64_t seed,
                                                           std::uint32_t strata_scale,
                                                           const std::function<bool()>& stop) {
  std::vector<std::uint32_t> groups;
  for (std::uint32_t g = 0; g < s.groups.size(); ++g) {
    if (s.groups[g].next_event) groups.push_back(g);
  }
  if (groups.empty()) return std::vector<DirectPart>{};
  Evaluator eval(s, backend, seed, stop);
  // Targets given back to the photons keep zero parts (their photons deposit bounce 0).
  for (const PreparedGrid& grid : s.grids) {
    if (grid.indirect_only || grid.direct_by_photons) continue;
    for (std::uint32_t iv = 0; iv < grid.nv; ++iv) {
      for (std::uint32_t iu = 0; iu < grid.nu; ++iu) {
        Domain d = cell_domain(grid, iu, iv);
        d.strata = kCellStrataSide * strata_scale;
        for (const std::uint32_t g : groups) eval.add(d, g);
      }
    }
  }
  const std::vector<std::uint32_t> bins = surface_bins(s, true);
  std::vector<Surface> surfaces;  // kept alive until finish(): the jobs point at them
  surfaces.reserve(bins.size());
  for (const std::uint32_t bin : bins) {
    surfaces.push_back(surface_of(s, bin));
    if (surfaces.back().cdf.empty()) continue;
    Domain d;
    d.bin = bin;
    d.surface = &surfaces.back();
    d.strata = kSurfaceStrata * strata_scale * strata_scale;
    for (const std::uint32_t g : groups) eval.add(d, g);
  }
  std::vector<DirectPart> parts = eval.finish();
  if (eval.stopped()) return std::nullopt;
  // A whole grid's bin: the mean of its cells (equal areas), their variances over C^2.
  for (const PreparedGrid& grid : s.grids) {
    if (grid.indirect_only || grid.direct_by_photons) continue;
    const double cells = double(grid.nu) * grid.nv;
    for (const std::uint32_t g : groups) {
      const std::size_t base = g * s.bins.size();
      DirectPart whole;
      for (std::uint32_t c = 0; c < grid.nu * grid.nv; ++c) {
        const DirectPart& p = parts[base + grid.bin + 1 + c];
        whole.lux += p.lux / cells;
        whole.variance += p.variance / (cells * cells);
        whole.lit += p.lit;
      }
      parts[base + grid.bin] = whole;
    }
  }
  return parts;
}

}  // namespace lightsolver::detail
