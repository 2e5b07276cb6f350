#pragma once
/// \file scene_io.hpp
/// Reading scene files (docs/scene-format.md) and mesh files (PLY, OBJ).

#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "lightsolver/scene.hpp"

namespace lightsolver {

/// Reads and validates a scene file. Mesh and photometric files are resolved relative to it.
/// Throws InputError naming the file and field.
Scene load_scene(const std::string& path);

/// Parses a scene from JSON text. `file` is used in messages, `base_dir` resolves relative paths.
Scene scene_from_json(const std::string& text, const std::string& file,
                      const std::string& base_dir);

/// Reads one material of a scene file's "materials" object (`type` and the type's keys; the
/// keys left out keep default_material()'s values). Values are range-checked later, by
/// validate(). `where` names the entry in messages.
Material material_from_json(const std::string& name, const nlohmann::json& entry,
                            const std::string& where);

/// Reads one luminaire entry of a scene file's "luminaires" list (name, type and the type's
/// keys, as docs/scene-format.md lists them) through the luminaire-type table, so callers need
/// no code per type. Values are range-checked later, by validate(). `where` names the entry
/// in messages; `base_dir` resolves a photometric file.
Luminaire luminaire_from_json(const nlohmann::json& entry, const std::string& where,
                              const std::string& base_dir);

/// Reads one target entry of a scene file's "targets" list; a surface target's mesh is looked
/// up in `scene`.
Target target_from_json(const nlohmann::json& entry, const std::string& where, const Scene& scene);

/// Reads all triangles of a PLY or OBJ file (every mesh in it, concatenated). Throws InputError
/// naming the file when it is missing, unreadable or has no triangles.
Mesh load_mesh_file(const std::string& path);

}  // namespace lightsolver
