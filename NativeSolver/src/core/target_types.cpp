// The target types, one section each: scene-file keys, value checks, tallies and results.
// Numbers and messages are those the reader, validator, prepare() and make_target had before
// the table; the golden results (Tests/golden) pin that nothing moved.
#include "core/target_types.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "core/json_reader.hpp"
#include "glare/observer_grid.hpp"
#include "glare/observer_target.hpp"

namespace lightsolver::detail {

Estimate TargetTallies::estimate(std::uint32_t b) const {
  return tallies.estimate(b, bins[b].area_m2, confidence);
}

Estimate TargetTallies::estimate_z(std::uint32_t b, double z) const {
  return tallies.estimate_z(b, bins[b].area_m2, z);
}

namespace {

// Numbers in messages: 6 significant digits, as the validator prints them.
std::string show(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

vec3 local(const glm::dvec3& p, const glm::dvec3& origin) { return vec3(p - origin); }

std::optional<glm::dvec3> no_anchor(const Target&) { return std::nullopt; }
std::optional<glm::dvec3> at_corner(const Target& t) { return t.corner; }
std::optional<glm::dvec3> at_position(const Target& t) { return t.position; }

void no_result(const TargetTallies&, TargetResult&) {}

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

// An eye's tally: a virtual square of kObserverSquare_m side centred on the eye, facing the line
// of sight (light travelling toward the eye from the viewed half-space crosses it against its
// normal), counting only reflected light, into its kEyeBins bins from `bin`.
void add_eye(const glm::dvec3& eye, const glm::dvec3& view, const glm::dvec3& up_hint,
             const std::string& name, std::uint32_t bin, PreparedScene& out) {
  Target square;
  const glm::dvec3 v = glm::normalize(view);
  const glm::dvec3 side = glm::normalize(glm::cross(v, up_hint));
  const glm::dvec3 up = glm::cross(v, side);  // side x up = v: the square's normal is v
  square.edge1 = kObserverSquare_m * side;
  square.edge2 = kObserverSquare_m * up;
  square.corner = eye - 0.5 * (square.edge1 + square.edge2);
  square.nu = square.nv = 1;
  PreparedGrid g = prepare_grid(square, out.origin, bin);
  g.indirect_only = 1;
  out.grids.push_back(g);
  out.observers.push_back(name);
}

// The bins and grid rows of a target with `eyes` eyes (all its eyes' squares first, then a
// grid row per eye, eye k's at point_bin(k)); `add(k, bin)` adds eye k's row.
template <class AddEye>
void prepare_eyes(std::uint32_t eyes, PreparedScene& out, AddEye add) {
  PreparedTarget rec = append_target_bins(out.bins, kObserverSquare_m * kObserverSquare_m, 0, eyes);
  rec.first_grid = static_cast<std::uint32_t>(out.grids.size());
  rec.grid_rows = eyes;
  for (std::uint32_t k = 0; k < eyes; ++k) add(k, rec.point_bin(k));
  out.targets.push_back(rec);
}

std::uint32_t no_eyes(const Target&) { return 0; }
std::uint32_t one_eye(const Target&) { return 1; }

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

constexpr const char* kGridKeys[] = {"name",  "type",  "corner",       "edge1",
                                     "edge2", "cells", "requirements", "task"};

void read_grid(const JsonNode& n, const Scene&, Target& t) {
  n.require_object(kGridKeys);
  t.corner = n.at("corner").vec3();
  t.edge1 = n.at("edge1").vec3();
  t.edge2 = n.at("edge2").vec3();
  read_cells(n, t, limits::kMaxGridCells, "more than 10^7 cells in one grid");
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
}

// --- observer: an eye's reflected light, and its UGR ----------------------------------------

constexpr const char* kObserverKeys[] = {"name", "type",         "position", "view_direction",
                                         "up",   "requirements", "task"};

void read_observer(const JsonNode& n, const Scene&, Target& t) {
  n.require_object(kObserverKeys);
  t.position = n.at("position").vec3();
  t.view_direction = n.at("view_direction").vec3();
  if (n.has("up")) t.up = n.at("up").vec3();
}

// Checks `up` and makes it unit length.
void check_up(const TargetChecks& c, Target& t) {
  c.direction("up", t.up);
  t.up = glm::normalize(t.up);
}

bool across(const glm::dvec3& view, const glm::dvec3& up) {
  return glm::length(glm::cross(view, up)) >= 1e-6;
}

// An eye inside the coordinate range, a line of sight and an up direction that are not
// parallel (normalised here; up is made orthogonal to the line of sight when used).
void check_observer(const TargetChecks& c, Target& t) {
  c.coordinates("position", t.position);
  c.direction("view_direction", t.view_direction);
  c.direction("up", t.up);
  t.view_direction = glm::normalize(t.view_direction);
  t.up = glm::normalize(t.up);
  if (!across(t.view_direction, t.up)) {
    c.fail("up",
           "is parallel to view_direction: the observer needs an up "
           "direction across its line of sight (default +z)");
  }
}

void prepare_observer(const Target& t, const std::vector<double>&, PreparedScene& out) {
  prepare_eyes(1, out, [&](std::uint32_t, std::uint32_t bin) {
    add_eye(t.position, t.view_direction, t.up, t.name, bin, out);
  });
}

void observer_result(const TargetTallies& tt, TargetResult& r) {
  r.is_observer = true;
  if (tt.luminaires != nullptr) r.glare = observer_glare(tt.target, *tt.luminaires, r.estimate);
}

// --- observer grid: eyes x lines of sight, and the largest UGR ------------------------------

constexpr const char* kObserverGridKeys[] = {
    "name",          "type", "positions",    "corner", "edge1", "edge2", "cells", "view_directions",
    "view_step_deg", "up",   "requirements", "task"};

void read_observer_grid(const JsonNode& n, const Scene&, Target& t) {
  n.require_object(kObserverGridKeys);
  if (n.has("positions")) {
    for (const char* key : {"corner", "edge1", "edge2", "cells"}) {
      if (n.has(key)) n.fail("give either \"positions\" or corner, edge1, edge2 and cells");
    }
    const JsonNode list = n.at("positions");
    if (list.array_size() == 0) list.fail("must list at least one eye position");
    if (list.array_size() > limits::kMaxObserverGridPoints) {
      list.fail("more than 1024 eye positions");
    }
    for (std::size_t i = 0; i < list.array_size(); ++i) t.positions.push_back(list[i].vec3());
  } else {
    t.corner = n.at("corner").vec3();
    t.edge1 = n.at("edge1").vec3();
    t.edge2 = n.at("edge2").vec3();
    read_cells(n, t, limits::kMaxObserverGridPoints, "more than 1024 eye positions");
  }
  if (n.has("view_directions") == n.has("view_step_deg")) {
    n.fail("give either \"view_directions\" or \"view_step_deg\"");
  }
  if (n.has("view_step_deg")) t.view_step_deg = n.at("view_step_deg").number();
  if (n.has("view_directions")) {
    const JsonNode list = n.at("view_directions");
    if (list.array_size() == 0) list.fail("must list at least one view direction");
    if (list.array_size() > limits::kMaxObserverGridPoints) {
      list.fail("more than 1024 view directions");
    }
    for (std::size_t i = 0; i < list.array_size(); ++i) {
      t.view_directions.push_back(list[i].vec3());
    }
  }
  if (n.has("up")) t.up = n.at("up").vec3();
}

// The eyes: listed, or the rectangle's cells (within 1024, each cell centre in range).
std::uint64_t check_positions(const TargetChecks& c, const Target& t) {
  if (!t.positions.empty()) {
    for (std::size_t i = 0; i < t.positions.size(); ++i) {
      c.coordinates("positions[" + std::to_string(i) + "]", t.positions[i]);
    }
    return t.positions.size();
  }
  c.parallelogram(t, "the rectangle of eye positions has zero area");
  const std::uint64_t count = std::uint64_t(t.nu) * t.nv;
  if (t.nu == 0 || t.nv == 0) c.fail("cells", "need at least 1x1 eye positions");
  if (count > limits::kMaxObserverGridPoints) {
    c.fail("cells", std::to_string(count) + " eye positions, more than 1024");
  }
  return count;
}

// The lines of sight: listed (each across `up`), or a step that divides the full turn.
std::uint64_t check_directions(const TargetChecks& c, Target& t) {
  if (t.view_step_deg) {
    const double step = *t.view_step_deg;
    const double turns = 360.0 / step;
    if (!(step > 0.0 && step <= 360.0) || std::abs(turns - std::round(turns)) > 1e-9 * turns) {
      c.fail("view_step_deg",
             "must be > 0 and divide 360 (e.g. 15, 45, 90; got " + show(step) + ")");
    }
    // Before the count is converted: a tiny step gives an infinite or huge one.
    if (!(turns <= double(limits::kMaxObserverGridPoints))) {
      c.fail("view_step_deg", "gives " + show(turns) + " view directions, more than 1024");
    }
    if (!t.view_directions.empty()) c.fail("view_directions", "give it or view_step_deg, not both");
    return static_cast<std::uint64_t>(std::round(turns));
  }
  if (t.view_directions.empty()) {
    c.fail("view_directions", "must list at least one view direction (or give view_step_deg)");
  }
  for (std::size_t i = 0; i < t.view_directions.size(); ++i) {
    const std::string key = "view_directions[" + std::to_string(i) + "]";
    c.direction(key, t.view_directions[i]);
    t.view_directions[i] = glm::normalize(t.view_directions[i]);
    if (!across(t.view_directions[i], t.up)) {
      c.fail(key, "is parallel to up: an eye needs an up direction across its line of sight");
    }
  }
  return t.view_directions.size();
}

void check_observer_grid(const TargetChecks& c, Target& t) {
  check_up(c, t);
  const std::uint64_t positions = check_positions(c, t);
  const std::uint64_t directions = check_directions(c, t);
  if (positions * directions > limits::kMaxObserverGridPoints) {
    c.fail(t.positions.empty() ? "cells" : "positions",
           std::to_string(positions) + " positions x " + std::to_string(directions) +
               " view directions = " + std::to_string(positions * directions) +
               " eyes, more than 1024 (each is a tally every ray segment is tested against)");
  }
}

std::optional<glm::dvec3> observer_grid_anchor(const Target& t) {
  return t.positions.empty() ? t.corner : t.positions.front();
}

// Eyes x lines of sight, eye-major (observer_grid_positions, observer_grid_directions).
std::uint32_t observer_grid_eyes(const Target& t) {
  return static_cast<std::uint32_t>(observer_grid_positions(t).size() *
                                    observer_grid_directions(t).size());
}

void prepare_observer_grid(const Target& t, const std::vector<double>&, PreparedScene& out) {
  const std::vector<glm::dvec3> positions = observer_grid_positions(t);
  const std::vector<glm::dvec3> directions = observer_grid_directions(t);
  const auto eyes = static_cast<std::uint32_t>(positions.size() * directions.size());
  prepare_eyes(eyes, out, [&](std::uint32_t k, std::uint32_t bin) {
    add_eye(positions[k / directions.size()], directions[k % directions.size()], t.up, t.name, bin,
            out);
  });
}

void observer_grid_result(const TargetTallies& tt, TargetResult& r) {
  const PreparedTarget& at = tt.layout;
  const ObserverGridTallies points{
      [&tt, &at](std::size_t k) { return tt.estimate(at.point_bin(std::uint32_t(k))); },
      [&tt, &at](std::size_t k, double z) {
        return tt.estimate_z(at.point_bin(std::uint32_t(k)), z);
      }};
  if (tt.observer_grid == nullptr && tt.luminaires == nullptr) {
    throw std::logic_error("an observer grid's result needs the scene's luminaires");
  }
  // Traced: the geometry from the scene's luminaires; rescaled: from the results, dimmed.
  ObserverGridOutcome o = observer_grid_glare(
      tt.target.name,
      tt.observer_grid ? *tt.observer_grid : observer_grid_geometry(tt.target, *tt.luminaires),
      tt.confidence, points);
  r.estimate = points.estimate(o.estimate_point);
  r.glare = std::move(o.max);
  r.observer_grid = std::move(o.grid);
}

using T = Target::Type;
constexpr unsigned kIlluminance = kRequireEm | kRequireU0 | kRequireEmin | kRequireUd;
// The results-file keys each type's result adds (results_io.cpp's target_json, add_glare,
// add_grid_intervals: the intervals only when requirements are judged).
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
                                       "ud_ci_high"};
constexpr const char* kGlareFields[] = {"background_luminance_cd_m2",
                                        "background_ci_low_cd_m2",
                                        "background_ci_high_cd_m2",
                                        "ugr",
                                        "ugr_ci_low",
                                        "ugr_ci_high",
                                        "luminaires",
                                        "warnings"};
constexpr const char* kObserverGridFields[] = {"background_luminance_cd_m2",
                                               "background_ci_low_cd_m2",
                                               "background_ci_high_cd_m2",
                                               "ugr",
                                               "ugr_ci_low",
                                               "ugr_ci_high",
                                               "luminaires",
                                               "warnings",
                                               "observer_grid"};

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
    {.type = T::Observer,
     .name = "observer",
     .keys = kObserverKeys,
     .read = read_observer,
     .check = check_observer,
     .requirements = kRequireUgr,
     .other_requirements = "an observer target has only ugr_max (illuminance needs a grid)",
     .tally = TallyKind::GridRows,
     .cells = false,
     .eyes = one_eye,
     .anchor = at_position,
     .prepare = prepare_observer,
     .result = observer_result,
     .result_fields = kGlareFields},
    {.type = T::ObserverGrid,
     .name = "observer_grid",
     .keys = kObserverGridKeys,
     .read = read_observer_grid,
     .check = check_observer_grid,
     .requirements = kRequireUgr,
     .other_requirements = "an observer grid has only ugr_max (illuminance needs a grid)",
     .tally = TallyKind::GridRows,
     .cells = false,
     .eyes = observer_grid_eyes,
     .anchor = observer_grid_anchor,
     .prepare = prepare_observer_grid,
     .result = observer_grid_result,
     .result_fields = kObserverGridFields},
}};

}  // namespace

std::span<const TargetType> target_types() { return kTypes; }

const TargetType& target_type(Target::Type type) {
  for (const auto& row : kTypes) {
    if (row.type == type) return row;
  }
  throw std::logic_error("target type without a row in target_types.cpp");
}

const TargetType* find_target_type(std::string_view name) {
  for (const auto& row : kTypes) {
    if (name == row.name) return &row;
  }
  return nullptr;
}

std::string target_type_names() {
  std::string s;
  for (std::size_t i = 0; i < kTypes.size(); ++i) {
    if (i > 0) s += i + 1 == kTypes.size() ? " or " : ", ";
    s += kTypes[i].name;
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

std::vector<glm::dvec3> observer_grid_positions(const Target& t) {
  if (!t.positions.empty()) return t.positions;
  std::vector<glm::dvec3> eyes;
  for (std::uint32_t iv = 0; iv < t.nv; ++iv) {
    for (std::uint32_t iu = 0; iu < t.nu; ++iu) {
      eyes.push_back(t.corner + (iu + 0.5) / t.nu * t.edge1 + (iv + 0.5) / t.nv * t.edge2);
    }
  }
  return eyes;
}

std::vector<glm::dvec3> observer_grid_directions(const Target& t) {
  if (!t.view_step_deg) return t.view_directions;
  const glm::dvec3 up = glm::normalize(t.up);
  glm::dvec3 start = glm::dvec3(1, 0, 0) - up.x * up;  // +x in the plane across up
  if (glm::length(start) < 1e-6) start = glm::dvec3(0, 1, 0) - up.y * up;
  start = glm::normalize(start);
  const glm::dvec3 left = glm::cross(up, start);  // counter-clockwise seen from above
  const auto count = static_cast<std::size_t>(std::round(360.0 / *t.view_step_deg));
  std::vector<glm::dvec3> views;
  for (std::size_t k = 0; k < count; ++k) {
    const double a = k * *t.view_step_deg * std::numbers::pi / 180.0;
    views.push_back(std::cos(a) * start + std::sin(a) * left);
  }
  return views;
}

}  // namespace lightsolver::detail
