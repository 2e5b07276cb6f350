#pragma once
// The two ways a mesh file is read (mesh_io.cpp): load_mesh_file() takes the direct one where it
// applies. Both are here so a test can check that they give the same mesh.
#include <optional>
#include <string>

#include "lightsolver/scene.hpp"

namespace lightsolver::detail {

// The workbench's PLY layout (binary little-endian; vertex: float x, y, z; face: a uchar-counted
// int or uint list, every face a triangle) read directly; nullopt for anything else, an index out
// of range included, which Assimp then reads (and reports).
std::optional<Mesh> read_simple_ply(const std::string& path);

// Any PLY or OBJ file through Assimp (triangulated; no welding, smoothing or re-orientation).
Mesh read_mesh_with_assimp(const std::string& path);

}  // namespace lightsolver::detail
