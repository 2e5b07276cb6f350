#pragma once
// `within` polygons of position and translation variables: the cells of a placement rectangle
// that lie on an L-shaped ceiling, around a column, inside a room that is not a rectangle.
#include <functional>
#include <glm/vec2.hpp>
#include <vector>

#include "io/json_reader.hpp"
#include "lightsolver/optimizer/domain.hpp"
#include "lightsolver/optimizer/scene_problem.hpp"

namespace lightsolver::optimizer::regions {

/// Reads `within` into the variable's rectangle coordinates (u along edge1, v along edge2;
/// points off the rectangle's plane are projected onto it): either one polygon
/// ([[x, y, z], ...], world metres, in order around it) or {"outer": polygon, "holes":
/// [polygon, ...]} (columns, shafts). Fails naming the field for a ring of fewer than 3 points
/// or without area, or a region that holds no cell centre of the rectangle.
PlacementRegion read_region(const lightsolver::detail::JsonNode& within, const SceneVariable& v,
                            const Domain& domain);

/// Even-odd test over all rings (a point inside a hole is outside; on an edge: either way).
bool inside(const PlacementRegion& region, glm::dvec2 q);

/// The search's admissible filter: every variable with a region has its cell centre inside it.
/// Empty when no variable has one.
std::function<bool(const Configuration&)> admissible_filter(const SceneProblem& p);

/// Luminaires never share a place: every luminaire moved by a position variable keeps its
/// anchor at least max(p.min_spacing_m, 1 µm) from the anchors of the luminaires of the other
/// position variables and of the luminaires no variable moves. (Luminaires moved together by
/// one variable keep their own offsets.) Empty when no position variable could collide.
std::function<bool(const Configuration&)> spacing_filter(const SceneProblem& p);

/// Both filters (either may be empty; empty when both are).
std::function<bool(const Configuration&)> both(std::function<bool(const Configuration&)> a,
                                               std::function<bool(const Configuration&)> b);

}  // namespace lightsolver::optimizer::regions
