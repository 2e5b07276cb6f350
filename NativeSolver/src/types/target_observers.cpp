// The eye target types, observer and observer grid: an eye's reflected light in a virtual
// square (kEyeBins bins each) and its UGR; their rows of the table in target_types.cpp.
#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>
#include <stdexcept>

#include "io/json_reader.hpp"
#include "types/target_rows.hpp"

namespace lightsolver::detail {
namespace {

using namespace target_rows;

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

std::uint32_t one_eye(const Target&) { return 1; }

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

// The observer rows' result hooks are glare's (src/glare/observer_rows.cpp): glare sits above
// core, and the type table (src/tables/target_table.cpp, target_types()) puts them in.
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

}  // namespace

TargetType observer_target_type() {
  return {.type = Target::Type::Observer,
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
          .result = nullptr,
          .result_fields = kGlareFields};
}

TargetType observer_grid_target_type() {
  return {.type = Target::Type::ObserverGrid,
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
          .result = nullptr,
          .result_fields = kObserverGridFields};
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
