// The target types, one section each: scene-file keys, value checks, tallies and results.
// Numbers and messages are those the reader, validator, prepare() and make_target had before
// the table; the golden results (Tests/golden) pin that nothing moved.
#include "types/target_types.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "io/json_reader.hpp"
#include "types/target_rows.hpp"

namespace lightsolver::detail {

Estimate TargetTallies::estimate(std::uint32_t b) const {
  return tallies.estimate(b, bins[b].area_m2, confidence);
}

Estimate TargetTallies::estimate_z(std::uint32_t b, double z) const {
  return tallies.estimate_z(b, bins[b].area_m2, z);
}

namespace {
vec3 local(const glm::dvec3& p, const glm::dvec3& origin) { return vec3(p - origin); }
}  // namespace

namespace target_rows {

// Numbers in messages: 6 significant digits, as the validator prints them.
std::string show(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

std::optional<glm::dvec3> at_position(const Target& t) { return t.position; }

// "cells": [nu, nv], each >= 1, at most `most` together.
void read_cells(const JsonNode& n, Target& t, std::uint64_t most, const char* too_many) {
  const JsonNode cells = n.at("cells");
  if (cells.array_size() != 2) cells.fail("expected [nu, nv]");
  const std::uint64_t nu = cells[0].unsigned_integer(), nv = cells[1].unsigned_integer();
  if (nu == 0 || nv == 0) cells.fail("a grid needs at least 1x1 cells");
  // Each factor first: nu * nv must not wrap around in 64 bits before the comparison.
  if (nu > most || nv > most || nu * nv > most) cells.fail(too_many);
  t.nu = static_cast<std::uint32_t>(nu);
  t.nv = static_cast<std::uint32_t>(nv);
}

// A grid row over the target's rectangle, its whole-grid bin at `bin`.
PreparedGrid prepare_grid(const Target& t, const glm::dvec3& origin, std::uint32_t bin) {
  PreparedGrid g;
  const glm::dvec3 n = glm::normalize(glm::cross(t.edge1, t.edge2));
  const glm::dvec3 du = glm::cross(t.edge2, n), dv = glm::cross(n, t.edge1);
  g.corner = local(t.corner, origin);
  g.normal = vec3(n);
  g.du = vec3(du / glm::dot(t.edge1, du));
  g.dv = vec3(dv / glm::dot(t.edge2, dv));
  g.nu = t.nu;
  g.nv = t.nv;
  g.bin = bin;
  return g;
}

}  // namespace target_rows

namespace {

using namespace target_rows;

std::optional<glm::dvec3> no_anchor(const Target&) { return std::nullopt; }
std::optional<glm::dvec3> at_corner(const Target& t) { return t.corner; }
std::uint32_t no_eyes(const Target&) { return 0; }
void no_result(const TargetTallies&, TargetResult&) {}

// --- surface: a mesh's absorbed and reflected light -----------------------------------------

constexpr const char* kSurfaceKeys[] = {"name", "type", "mesh", "requirements", "task"};

void read_surface(const JsonNode& n, const Scene& scene, Target& t) {
  n.require_object(kSurfaceKeys);
  const std::string mesh = n.at("mesh").string();
  t.mesh = scene.find_mesh(mesh);
  if (t.mesh < 0) n.at("mesh").fail("unknown mesh \"" + mesh + "\"");
}

double mesh_area_m2(const Mesh& m) {
  double area = 0.0;
  for (const auto& t : m.triangles) {
    area += 0.5 * glm::length(glm::cross(m.vertices[t[1]] - m.vertices[t[0]],
                                         m.vertices[t[2]] - m.vertices[t[0]]));
  }
  return area;
}

void check_surface(const TargetChecks& c, Target& t) {
  const Mesh* m = c.mesh(t.mesh);
  if (!m) return;
  if (m->triangles.empty()) {
    c.fail("mesh", "mesh \"" + m->name + "\" has zero area (no usable triangle)");
  }
  const double area = mesh_area_m2(*m);
  if (!(area >= limits::kMinArea_m2)) {
    c.fail("mesh", "mesh \"" + m->name + "\" has an area of " + show(area) +
                       " m2, below (1 um)^2 = 1e-12 m2");
  }
}

void prepare_surface(const Target& t, const std::vector<double>& mesh_area, PreparedScene& out) {
  PreparedMesh& m = out.meshes[t.mesh];
  PreparedTarget rec;
  if (m.bin < 0) {  // two targets naming one mesh share its bin
    rec = append_target_bins(out.bins, mesh_area[t.mesh], 0, 0);
    m.bin = static_cast<std::int32_t>(rec.bin);
  }
  rec.bin = static_cast<std::uint32_t>(m.bin);
  rec.mesh = t.mesh;
  rec.first_grid = static_cast<std::uint32_t>(out.grids.size());
  out.targets.push_back(rec);
}

// --- grid: a virtual rectangle of cells (light crossing it from the front) ------------------

constexpr const char* kGridKeys[] = {"name",  "type",         "corner", "edge1",   "edge2",
                                     "cells", "requirements", "task",   "quantity"};

void read_grid(const JsonNode& n, const Scene&, Target& t) {
  n.require_object(kGridKeys);
  t.corner = n.at("corner").vec3();
  t.edge1 = n.at("edge1").vec3();
  t.edge2 = n.at("edge2").vec3();
  read_cells(n, t, limits::kMaxGridCells, "more than 10^7 cells in one grid");
  if (n.has("quantity")) {
    const std::string q = n.at("quantity").string();
    if (q == "daylight_factor") {
      t.quantity = Target::Quantity::DaylightFactor;
    } else if (q != "illuminance") {
      n.at("quantity").fail("expected \"illuminance\" or \"daylight_factor\", got \"" + q + "\"");
    }
  }
}

// Grids divide flux by their cells' areas: sizes below 1 um are below any physical use (a
// 1 mm cell is fine) and would only make the estimates huge and meaningless.
void check_grid(const TargetChecks& c, Target& t) {
  c.parallelogram(t, "the grid has zero area");
  const double u_m = glm::length(t.edge1), v_m = glm::length(t.edge2);
  for (const auto& [key, length] : {std::pair{"edge1", u_m}, std::pair{"edge2", v_m}}) {
    if (length < limits::kMinGridEdge_m) {
      c.fail(key, "is " + show(length) + " m long, shorter than 1 um");
    }
  }
  if (t.nu == 0 || t.nv == 0) c.fail("cells", "need at least 1x1 cells");
  const std::uint64_t count = std::uint64_t(t.nu) * t.nv;
  if (count > limits::kMaxGridCells) {
    c.fail("cells", std::to_string(count) + " cells, more than 10^7 in one grid");
  }
  c.add_grid_cells(count);
  if (u_m / t.nu < limits::kMinGridEdge_m || v_m / t.nv < limits::kMinGridEdge_m) {
    c.fail("cells", "cells of " + show(u_m / t.nu) + " x " + show(v_m / t.nv) +
                        " m: a cell edge is shorter than 1 um");
  }
  const double cell_m2 = glm::length(glm::cross(t.edge1, t.edge2)) / double(count);
  if (cell_m2 < limits::kMinArea_m2) {
    c.fail("cells", "a cell's area is " + show(cell_m2) + " m2, below (1 um)^2 = 1e-12 m2");
  }
}

void prepare_grid_target(const Target& t, const std::vector<double>&, PreparedScene& out) {
  PreparedTarget rec =
      append_target_bins(out.bins, glm::length(glm::cross(t.edge1, t.edge2)), t.nu * t.nv, 0);
  rec.first_grid = static_cast<std::uint32_t>(out.grids.size());
  rec.grid_rows = 1;
  out.grids.push_back(prepare_grid(t, out.origin, rec.bin));
  out.grids.back().indirect_only = t.reflected_only ? 1 : 0;
  out.targets.push_back(rec);
}

// Cell and grid estimates at any alpha, for the simultaneous intervals of grid_intervals();
// z is computed once per alpha (the cells share it).
GridSampler grid_sampler(const TargetTallies& tt) {
  auto estimate = [&tt, alpha = -1.0, z = 0.0](std::uint32_t b, double a) mutable {
    if (a != alpha) z = z_for_alpha(alpha = a);
    return tt.estimate_z(b, z);
  };
  const PreparedTarget& at = tt.layout;
  return {
      at.cells, [estimate, at](double a) mutable { return estimate(at.bin, a); },
      [estimate, at](std::uint32_t c, double a) mutable { return estimate(at.cell_bin(c), a); }};
}

void grid_result(const TargetTallies& tt, TargetResult& r) {
  const Target& t = tt.target;
  r.is_grid = true;
  r.nu = t.nu;
  r.nv = t.nv;
  r.cells.reserve(tt.layout.cells);
  for (std::uint32_t c = 0; c < tt.layout.cells; ++c) {
    r.cells.push_back(tt.estimate(tt.layout.cell_bin(c)));
  }
  const auto [lo, hi] = std::minmax_element(r.cells.begin(), r.cells.end(),
                                            [](auto& a, auto& b) { return a.mean < b.mean; });
  r.min_lux = lo->mean;
  r.max_lux = hi->mean;
  r.uniformity = r.estimate.mean > 0.0 ? r.min_lux / r.estimate.mean : 0.0;
  if (tt.judged) {
    r.intervals =
        grid_intervals(grid_sampler(tt), tt.confidence, r.min_lux, r.max_lux, r.estimate.mean);
  }
  // A daylight-factor grid's daylight factor is the estimate layer's, added by the table
  // (src/tables/target_table.cpp).
}

using T = Target::Type;
constexpr unsigned kIlluminance = kRequireEm | kRequireU0 | kRequireEmin | kRequireUd;
// The results-file keys each type's result adds (results_io.cpp's target_json, add_glare,
// add_grid_intervals: the intervals whenever make_target computed them, as final results do).
constexpr const char* kGridFields[] = {"cells_uv",
                                       "cells",
                                       "min_lux",
                                       "max_lux",
                                       "uniformity",
                                       "min_ci_low_lux",
                                       "min_ci_high_lux",
                                       "max_ci_low_lux",
                                       "max_ci_high_lux",
                                       "uniformity_ci_low",
                                       "uniformity_ci_high",
                                       "ud",
                                       "ud_ci_low",
                                       "ud_ci_high",
                                       "daylight_factor"};  // daylight-factor grids
const std::array<TargetType, 4> kTypes = {{
    {.type = T::Surface,
     .name = "surface",
     .keys = kSurfaceKeys,
     .read = read_surface,
     .check = check_surface,
     .requirements = kRequireEm,
     .other_requirements = "a surface target has no cells: only em_lux applies to it (use a "
                           "grid target for U0, Emin and Ud)",
     .tally = TallyKind::MeshBin,
     .cells = false,
     .eyes = no_eyes,
     .anchor = no_anchor,
     .prepare = prepare_surface,
     .result = no_result,
     .result_fields = {}},
    {.type = T::Grid,
     .name = "grid",
     .keys = kGridKeys,
     .read = read_grid,
     .check = check_grid,
     .requirements = kIlluminance,
     .other_requirements = "",
     .tally = TallyKind::GridRows,
     .cells = true,
     .eyes = no_eyes,
     .anchor = at_corner,
     .prepare = prepare_grid_target,
     .result = grid_result,
     .result_fields = kGridFields},
    observer_target_type(),
    observer_grid_target_type(),
}};

}  // namespace

std::span<const TargetType> core_target_rows() { return kTypes; }

const TargetType& target_type(Target::Type type) {
  for (const auto& row : target_types()) {
    if (row.type == type) return row;
  }
  throw std::logic_error("target type without a row in target_types.cpp");
}

const TargetType* find_target_type(std::string_view name) {
  for (const auto& row : target_types()) {
    if (name == row.name) return &row;
  }
  return nullptr;
}

std::string target_type_names() {
  const std::span<const TargetType> rows = target_types();
  std::string s;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (i > 0) s += i + 1 == rows.size() ? " or " : ", ";
    s += rows[i].name;
  }
  return s;
}

PreparedTarget append_target_bins(std::vector<BinInfo>& bins, double area_m2, std::uint32_t cells,
                                  std::uint32_t eyes) {
  PreparedTarget rec;
  rec.bin = static_cast<std::uint32_t>(bins.size());
  if (eyes > 0) {
    rec.points = eyes;
    rec.point_stride = kEyeBins;
    rec.bin_count = kEyeBins * eyes;
    bins.resize(bins.size() + rec.bin_count, {area_m2});
    return rec;
  }
  rec.cells = cells;
  rec.bin_count = 1 + cells;
  bins.push_back({area_m2});
  bins.resize(bins.size() + cells, {cells > 0 ? area_m2 / double(cells) : 0.0});
  return rec;
}

}  // namespace lightsolver::detail
