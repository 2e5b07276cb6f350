#include "estimate/reflection_connection.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/geometric.hpp>
#include <numbers>

#include "lightsolver/error.hpp"

namespace lightsolver::detail {
namespace {

using glm::dvec3;

// The streams: PathRng stream kPathStream | group for the photons, kPointStream | group for the
// grid points; no photon group (< 2^26) and no next-event stream (2^31 | group) uses them.
constexpr std::uint32_t kPathStream = 0x40000000u;
constexpr std::uint32_t kPointStream = 0x20000000u;
// Per-path deposits kept per batch of paths (paths x cells doubles: 8 MiB), and the shadow rays
// of a batch (about two vertices per path): a batch is a cancellation point, as next_event.cpp's.
constexpr std::size_t kBatchValues = std::size_t(1) << 20;
constexpr std::size_t kConnectBatchRays = std::size_t(1) << 18;
// A shadow ray stops this fraction short of its grid point, which may lie on a surface (a
// grid on the floor): the photons' crossing there counts too (shared::grid_reach).
constexpr double kShortOfPoint = 1e-4;

// A grid row the connections reach: its cells as parallelograms.
struct GridCells {
  const PreparedGrid* grid;
  dvec3 corner, e1, e2, normal;  // e1, e2: one cell's edges
  double r0_sq;
  std::size_t first;  // its cells' first column in a path's deposits
};

// A grid row's whole edges, from its dual vectors (their Gram matrix's inverse), as
// next_event.cpp's cells.
void grid_edges(const PreparedGrid& g, dvec3& e1, dvec3& e2) {
  const dvec3 du(g.du), dv(g.dv);
  const double a = glm::dot(du, du), b = glm::dot(du, dv), c = glm::dot(dv, dv);
  const double det = a * c - b * b;
  e1 = (c * du - b * dv) / det;
  e2 = (a * dv - b * du) / det;
}

std::vector<GridCells> connected_grids(const PreparedScene& s) {
  std::vector<GridCells> out;
  std::size_t columns = 0;
  for (const PreparedGrid& g : s.grids) {
    if (g.indirect_only || !(g.connect_r0 > 0.0f)) continue;
    dvec3 e1, e2;
    grid_edges(g, e1, e2);
    const double r0 = g.connect_r0;
    out.push_back({&g, dvec3(g.corner), e1 / double(g.nu), e2 / double(g.nv),
                   glm::normalize(dvec3(g.normal)), r0 * r0, columns});
    columns += std::size_t(g.nu) * g.nv;
  }
  return out;
}

// One path's vertices connected to a point in every cell: `cells` gets its deposit (lx) per
// cell column.
void connect_path(const std::vector<GridCells>& grids, const PathVertex* v, std::size_t count,
                  double flux, PathRng& rng, Backend& backend, double* cells) {
  std::vector<ShadowRay> rays;
  std::vector<std::pair<std::size_t, double>> value;  // (column, lx) per ray
  for (std::size_t k = 0; k < count; ++k) {
    const dvec3 x(v[k].origin), nx(v[k].normal);
    const double scale = flux * v[k].reflectance / std::numbers::pi;
    for (const GridCells& g : grids) {
      for (std::uint32_t iv = 0; iv < g.grid->nv; ++iv) {
        for (std::uint32_t iu = 0; iu < g.grid->nu; ++iu) {
          const double a = iu + rng.uniform_double(), b = iv + rng.uniform_double();
          const dvec3 to = g.corner + a * g.e1 + b * g.e2 - x;
          const double d2 = glm::dot(to, to);
          if (!(d2 >= g.r0_sq)) continue;  // closer: the photons' own crossings count it
          const double d = std::sqrt(d2);
          const double cos_x = glm::dot(nx, to) / d, cos_y = -glm::dot(g.normal, to) / d;
          if (!(cos_x > 0.0 && cos_y > 0.0)) continue;  // behind x, or the grid's back
          rays.push_back({v[k].origin, float(d * (1.0 - kShortOfPoint)), vec3(to / d)});
          value.push_back(
              {g.first + std::size_t(iv) * g.grid->nu + iu, scale * cos_x * cos_y / d2});
        }
      }
    }
  }
  if (rays.empty()) return;
  std::vector<std::uint8_t> seen;
  backend.visible(rays, seen);
  for (std::size_t i = 0; i < rays.size(); ++i) {
    if (seen[i]) cells[value[i].first] += value[i].second;
  }
}

// Sums over paths of each column's deposit and its square, and the paths that reached it.
struct Sums {
  std::vector<double> sum, sum_sq;
  std::vector<std::uint64_t> lit;
};

// One group's M paths in batches; each path's deposits per cell column and per whole grid
// (the last columns: a grid's mean over its cells). False when `stop` asked before a batch.
bool group_sums(const PreparedScene& s, Backend& backend, const std::vector<GridCells>& grids,
                std::uint32_t group, std::uint64_t seed, std::uint64_t paths,
                const std::function<bool()>& stop, Sums& out) {
  const std::size_t cells =
      grids.empty()
          ? 0
          : grids.back().first + std::size_t(grids.back().grid->nu) * grids.back().grid->nv;
  const std::size_t columns = cells + grids.size();
  out = Sums{std::vector<double>(columns, 0.0), std::vector<double>(columns, 0.0),
             std::vector<std::uint64_t>(columns, 0)};
  const std::uint64_t batch =
      std::max<std::size_t>(1, std::min(kBatchValues / columns, kConnectBatchRays / (2 * cells)));
  const double flux = s.groups[group].flux_lm;
  std::vector<double> deposits;
  std::vector<PathVertex> vertices;
  for (std::uint64_t first = 0; first < paths; first += batch) {
    if (stop && stop()) return false;
    const std::uint64_t count = std::min(batch, paths - first);
    vertices.clear();
    backend.path_vertices(group, first, count, seed, kPathStream | group, vertices);
    // Each path's vertices: [starts[p], starts[p + 1]).
    std::vector<std::size_t> starts(count + 1, 0);
    for (const PathVertex& v : vertices) ++starts[v.path + 1];
    for (std::uint64_t p = 0; p < count; ++p) starts[p + 1] += starts[p];
    deposits.assign(count * columns, 0.0);
    tbb::parallel_for(std::uint64_t(0), count, [&](std::uint64_t p) {
      PathRng rng(seed, first + p, kPointStream | group);
      double* row = deposits.data() + p * columns;
      connect_path(grids, vertices.data() + starts[p], starts[p + 1] - starts[p], flux, rng,
                   backend, row);
      for (std::size_t gi = 0; gi < grids.size(); ++gi) {
        const std::size_t n = std::size_t(grids[gi].grid->nu) * grids[gi].grid->nv;
        double whole = 0.0;
        for (std::size_t c = 0; c < n; ++c) whole += row[grids[gi].first + c];
        row[cells + gi] = whole / double(n);
      }
    });
    // In path order: the sums do not depend on the schedule.
    for (std::uint64_t p = 0; p < count; ++p) {
      const double* row = deposits.data() + p * columns;
      for (std::size_t c = 0; c < columns; ++c) {
        out.sum[c] += row[c];
        out.sum_sq[c] += row[c] * row[c];
        out.lit[c] += row[c] > 0.0;
      }
    }
  }
  return true;
}

// Whether every material a photon can hit is diffuse (the connection's lobe).
bool all_diffuse(const PreparedScene& s, bool& reflects) {
  reflects = false;
  for (const PreparedMesh& m : s.meshes) {
    if (m.indices.empty()) continue;
    const Material& mat = s.materials[m.material];
    if (mat.type != Material::Type::Diffuse) return false;
    reflects = reflects || mat.reflectance > 0.0;
  }
  return true;
}

// The longer edge of a grid row's cells (m).
double cell_size(const PreparedGrid& g) {
  dvec3 e1, e2;
  grid_edges(g, e1, e2);
  return std::max(glm::length(e1) / g.nu, glm::length(e2) / g.nv);
}

}  // namespace

void plan_connection(PreparedScene& s, const Backend& backend, const std::string& mode,
                     bool goal_run, std::uint64_t photons) {
  for (PreparedGroup& g : s.groups) g.connect = false;
  for (PreparedGrid& g : s.grids) g.connect_r0 = 0.0f;
  const bool forced = mode == "on";
  const auto off = [&](const std::string& why) {
    s.connect_off = why;
    if (forced) throw InputError("", "connect_reflections", "\"on\", but " + why);
  };
  if (mode == "off") {
    s.connect_off = "off by the connect_reflections setting";
    return;
  }
  if (mode != "auto" && mode != "on") {
    throw InputError("", "connect_reflections", "must be \"auto\", \"on\" or \"off\"");
  }
  if (std::none_of(s.grids.begin(), s.grids.end(),
                   [](const PreparedGrid& g) { return !g.indirect_only; })) {
    return off("no grid target");
  }
  if (std::none_of(s.groups.begin(), s.groups.end(),
                   [](const PreparedGroup& g) { return g.next_event; })) {
    return off("no group has next-event estimation (next_event)");
  }
  bool reflects = false;
  if (!all_diffuse(s, reflects)) {
    return off("a mirror, glossy or glass surface (connections know diffuse reflection only)");
  }
  if (!reflects) return off("nothing reflects");
  if (!backend.traces_path_vertices()) {
    return off("the " + backend.name() + " backend traces no path vertices");
  }
  std::uint64_t cells = 0;
  for (const PreparedGrid& g : s.grids) cells += g.indirect_only ? 0 : std::uint64_t(g.nu) * g.nv;
  // Every group with next-event estimation traces its own paths.
  const auto groups = std::count_if(s.groups.begin(), s.groups.end(),
                                    [](const PreparedGroup& g) { return g.next_event; });
  const double fewest_rays = 2.0 * double(kConnectMinPaths) * double(cells) * double(groups);
  if (!goal_run && !forced && fewest_rays > 4.0 * kConnectRaysPerPhoton * double(photons)) {
    s.connect_off = "its fewest connections would take " +
                    std::to_string(std::uint64_t(fewest_rays)) + " shadow rays, more than " +
                    std::to_string(int(4 * kConnectRaysPerPhoton)) +
                    " per photon of the run (\"on\" traces them)";
    return;
  }
  for (PreparedGroup& g : s.groups) g.connect = g.next_event;
  for (PreparedGrid& g : s.grids) {
    if (!g.indirect_only) g.connect_r0 = float(kConnectR0Cells * cell_size(g));
  }
  s.connect_off.clear();
}

void drop_connection(PreparedScene& s, const std::string& why) {
  for (PreparedGroup& g : s.groups) g.connect = false;
  for (PreparedGrid& g : s.grids) g.connect_r0 = 0.0f;
  s.connect_off = why;
}

bool connection_pays(const PreparedScene& s, const std::vector<DirectPart>& direct,
                     const std::vector<DirectPart>& connected, std::string& why) {
  double direct_lux = 0.0, connected_lux = 0.0;
  for (std::uint32_t g = 0; g < s.groups.size(); ++g) {
    if (!s.groups[g].connect) continue;
    for (const PreparedGrid& grid : s.grids) {
      if (!(grid.connect_r0 > 0.0f)) continue;
      const std::size_t i = std::size_t(g) * s.bins.size() + grid.bin;  // the whole grid
      if (i < direct.size()) direct_lux += direct[i].lux;
      if (i < connected.size()) connected_lux += connected[i].lux;
    }
  }
  if (connected_lux >= kConnectMinShare * direct_lux) return true;
  char share[32];
  std::snprintf(share, sizeof share, "%.2g",
                direct_lux > 0.0 ? 100.0 * connected_lux / direct_lux : 0.0);
  why = "the connected reflected light at the grids was " + std::string(share) +
        " % of their direct light in its first paths, under " +
        std::to_string(int(100 * kConnectMinShare)) + " % (\"on\" connects)";
  return false;
}

std::uint64_t connection_paths(const PreparedScene& s, std::uint64_t photons) {
  std::uint64_t cells = 0;
  for (const PreparedGrid& g : s.grids) {
    if (!g.indirect_only && g.connect_r0 > 0.0f) cells += std::uint64_t(g.nu) * g.nv;
  }
  if (cells == 0 || std::none_of(s.groups.begin(), s.groups.end(),
                                 [](const PreparedGroup& g) { return g.connect; })) {
    return 0;
  }
  // A path is traced as a photon is: on a grid of few cells the shadow rays would ask for more
  // paths than photons, so at most a quarter of the photons (their cost, not the rays', then).
  const double fit = std::min(kConnectRaysPerPhoton * double(photons) / (2.0 * double(cells)),
                              kConnectMaxPathShare * double(photons));
  return std::max<std::uint64_t>(kConnectMinPaths, std::uint64_t(std::min(fit, 1e12)));
}

bool add_connected_reflection(const PreparedScene& s, Backend& backend, std::uint64_t seed,
                              std::uint64_t paths, std::vector<DirectPart>& direct,
                              const std::function<bool()>& stop) {
  const std::vector<GridCells> grids = connected_grids(s);
  if (grids.empty() || paths < 2) return true;
  const double m = double(paths);
  std::vector<DirectPart> out = direct;  // `direct` stays as it was if stopped
  for (std::uint32_t g = 0; g < s.groups.size(); ++g) {
    if (!s.groups[g].connect || !(s.groups[g].flux_lm > 0.0)) continue;
    Sums sums;
    if (!group_sums(s, backend, grids, g, seed, paths, stop, sums)) return false;
    const std::size_t base = std::size_t(g) * s.bins.size();
    const std::size_t cells = sums.sum.size() - grids.size();
    const auto add = [&](std::uint32_t bin, std::size_t column) {
      const double mean = sums.sum[column] / m;
      // The sample variance over the paths, over M: the variance of their mean.
      const double spread = std::max(0.0, sums.sum_sq[column] - m * mean * mean);
      DirectPart& part = out[base + bin];
      part.lux += mean;
      part.variance += spread / (m - 1.0) / m;
      part.lit += sums.lit[column];
    };
    for (std::size_t gi = 0; gi < grids.size(); ++gi) {
      const PreparedGrid& grid = *grids[gi].grid;
      for (std::uint32_t c = 0; c < grid.nu * grid.nv; ++c) {
        add(grid.bin + 1 + c, grids[gi].first + c);
      }
      add(grid.bin, cells + gi);
    }
  }
  direct = std::move(out);
  return true;
}

}  // namespace lightsolver::detail
