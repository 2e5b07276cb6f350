// PLY and OBJ reading through Assimp (well kept, handles ASCII and binary PLY and OBJ quirks).
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <filesystem>

#include "lightsolver/scene_io.hpp"

namespace lightsolver {

Mesh load_mesh_file(const std::string& path) {
  namespace fs = std::filesystem;
  if (!fs::is_regular_file(path)) throw InputError(path, "", "mesh file not found");
  const std::string ext = fs::path(path).extension().string();
  if (ext != ".ply" && ext != ".PLY" && ext != ".obj" && ext != ".OBJ") {
    throw InputError(path, "", "unsupported mesh format \"" + ext + "\" (use .ply or .obj)");
  }
  Assimp::Importer importer;
  // Only triangulation: no welding, smoothing or re-orientation, so winding and positions stay
  // exactly as written (the winding decides which side of a target is its front).
  const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate);
  if (!scene || !scene->mRootNode) {
    throw InputError(path, "", std::string("cannot read mesh: ") + importer.GetErrorString());
  }
  Mesh mesh;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* in = scene->mMeshes[m];
    const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
    for (unsigned v = 0; v < in->mNumVertices; ++v) {
      const aiVector3D& p = in->mVertices[v];
      mesh.vertices.emplace_back(p.x, p.y, p.z);
    }
    for (unsigned f = 0; f < in->mNumFaces; ++f) {
      const aiFace& face = in->mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines carry no area
      mesh.triangles.emplace_back(base + face.mIndices[0], base + face.mIndices[1],
                                  base + face.mIndices[2]);
    }
  }
  if (mesh.triangles.empty()) throw InputError(path, "", "the mesh file holds no triangle");
  return mesh;
}

}  // namespace lightsolver
