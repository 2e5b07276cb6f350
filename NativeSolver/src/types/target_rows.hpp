#pragma once
// What the target types' rows share across their files (target_types.cpp holds the table and
// the surface and grid rows, target_observers.cpp the observer and observer-grid rows).
#include <cstdint>
#include <glm/vec3.hpp>
#include <optional>
#include <string>

#include "model/prepared_scene.hpp"
#include "types/target_types.hpp"

namespace lightsolver::detail {

namespace target_rows {

/// Numbers in messages: 6 significant digits, as the validator prints them.
std::string show(double v);
/// Reads "cells": [nu, nv], each >= 1, at most `most` together (`too_many`: the message).
void read_cells(const JsonNode& n, Target& t, std::uint64_t most, const char* too_many);
/// A grid row over the target's rectangle, its whole-grid bin at `bin`.
PreparedGrid prepare_grid(const Target& t, const glm::dvec3& origin, std::uint32_t bin);
/// The target's position, for the scene's centre.
std::optional<glm::dvec3> at_position(const Target& t);

}  // namespace target_rows

/// The rows of target_observers.cpp.
TargetType observer_target_type();
TargetType observer_grid_target_type();

}  // namespace lightsolver::detail
