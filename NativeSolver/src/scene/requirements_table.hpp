#pragma once
// A target's requirements in a scene file: its "requirements" object and/or a "task" naming a
// row of the requirements table (Resources/requirements/en12464-1.json).
#include <string>

#include "lightsolver/compliance.hpp"

namespace lightsolver::detail {

class JsonNode;

/// Where the requirements table is found, first that exists: the file named by the
/// environment variable LIGHTSOLVER_REQUIREMENTS; en12464-1.json in the scene's folder
/// (`base_dir`, skipped when empty); the source tree's Resources/requirements/en12464-1.json
/// (compiled in). Empty when none exists.
std::string requirements_table_path(const std::string& base_dir);

/// Reads target `n`'s "task" (a table row, whose values come first) and "requirements" (its
/// keys replace the row's). Types here; ranges in validate(). InputError naming the field,
/// an unknown task listing the closest ids.
Requirements read_requirements(const JsonNode& n, const std::string& base_dir);

}  // namespace lightsolver::detail
