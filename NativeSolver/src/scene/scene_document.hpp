#pragma once
// One reading of a scene file for every reader: the parsed JSON beside the Scene read from it,
// so a reader of another block (the optimizer's `optimization`) neither parses the text again
// nor keeps its own copy of the file loader.
#include <nlohmann/json.hpp>
#include <string>

#include "lightsolver/scene.hpp"

namespace lightsolver::detail {

struct SceneDocument {
  nlohmann::json json;  // the whole file, parsed
  Scene scene;          // read and validated from `json`
};

// Parses `text` once and reads the scene from it (InputError names `file` and the field);
// `base_dir` resolves mesh and photometric files.
SceneDocument read_scene_document(const std::string& text, const std::string& file,
                                  const std::string& base_dir);

// The same from a file; relative paths are resolved from its folder.
SceneDocument load_scene_document(const std::string& path);

// A scene file's text (InputError when it cannot be opened or read).
std::string read_scene_text(const std::string& path);

// Reads the scene without validate(), for the scene check, which collects every validation
// error (validation_errors) instead of stopping at the first. Reading errors still throw.
Scene read_unvalidated_scene(const std::string& text, const std::string& file,
                             const std::string& base_dir);

}  // namespace lightsolver::detail
