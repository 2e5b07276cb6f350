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

}  // namespace lightsolver::detail
