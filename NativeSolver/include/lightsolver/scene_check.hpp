#pragma once
/// \file scene_check.hpp
/// The scene check the workbench and scripts run before a solve: the loader's and validate()'s
/// rules, plus the warnings a run would give before tracing (dropped triangles, photometric
/// file remarks, coincident surfaces, all luminaires at 0 lm). One validator for every caller.

#include <string>
#include <vector>

#include "lightsolver/scene.hpp"

namespace lightsolver {

/// One problem, located: `field` is a JSON path ("luminaires[0].flux_lm") or empty, `line` the
/// line of a file (photometric or mesh) when the problem is there, else 0.
struct SceneIssue {
  std::string file;
  std::string field;
  int line = 0;
  std::string message;
};

/// Errors stop a run; warnings do not. A file that cannot be read or parsed, or an entry that
/// cannot be read (a missing key, a wrong JSON type, an unreadable mesh or photometric file),
/// is one error; otherwise every entry's values are checked and each entry's first error is
/// listed (validation_errors). Warnings are complete when there is no error (they need a valid
/// scene).
struct SceneCheck {
  std::vector<SceneIssue> errors;
  std::vector<SceneIssue> warnings;
};

/// Checks a scene built in memory (a copy of it is validated and prepared; `scene` is left as
/// it is).
SceneCheck check_scene(const Scene& scene);

/// Reads and checks a scene file; a file that cannot be read or parsed is one error.
SceneCheck check_scene_file(const std::string& path);

/// Parses and checks scene JSON text; `file` names it in messages, `base_dir` resolves relative
/// mesh and photometric paths.
SceneCheck check_scene_json(const std::string& text, const std::string& file,
                            const std::string& base_dir);

/// The issue an InputError describes ("line 12" becomes `line`, anything else `field`).
SceneIssue issue_from_error(const InputError& error);

}  // namespace lightsolver
