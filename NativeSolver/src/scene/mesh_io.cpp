// PLY and OBJ reading through Assimp (well kept, handles ASCII and binary PLY and OBJ quirks),
// with a direct path for the one layout the workbench writes (binary little-endian, float x y z,
// triangles as uchar-counted int lists): Assimp takes ~10x longer on a 60k-triangle file, and
// the direct path gives the same vertices and triangles (Tests/native/core/mesh_io_test.cpp).
#include "scene/mesh_io.hpp"

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <dlfcn.h>

#include <bit>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>

#include "lightsolver/scene_io.hpp"

namespace lightsolver::detail {
namespace {

// The header's element counts when it is exactly the workbench's layout (comments allowed).
struct PlyLayout {
  std::size_t header_bytes = 0, vertices = 0, faces = 0;
};

std::optional<PlyLayout> simple_ply_layout(const std::string& data) {
  const std::size_t end = data.find("end_header\n");
  if (data.rfind("ply\n", 0) != 0 || end == std::string::npos) return std::nullopt;
  std::istringstream header(data.substr(0, end));
  std::string line;
  std::vector<std::string> lines;
  while (std::getline(header, line)) {
    if (line.rfind("comment", 0) == 0 || line.rfind("obj_info", 0) == 0) continue;
    lines.push_back(line);
  }
  PlyLayout layout;
  layout.header_bytes = end + std::strlen("end_header\n");
  const auto count = [](const std::string& l, const char* prefix, std::size_t& n) {
    if (l.rfind(prefix, 0) != 0) return false;
    const std::string digits = l.substr(std::strlen(prefix));
    if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos ||
        digits.size() > 12)
      return false;
    n = std::stoull(digits);
    return true;
  };
  const bool simple =
      lines.size() == 8 && lines[0] == "ply" && lines[1] == "format binary_little_endian 1.0" &&
      count(lines[2], "element vertex ", layout.vertices) && lines[3] == "property float x" &&
      lines[4] == "property float y" && lines[5] == "property float z" &&
      count(lines[6], "element face ", layout.faces) &&
      (lines[7] == "property list uchar int vertex_indices" ||
       lines[7] == "property list uchar uint vertex_indices");
  if (!simple) return std::nullopt;
  if (data.size() != layout.header_bytes + 12 * layout.vertices + 13 * layout.faces) {
    return std::nullopt;
  }
  return layout;
}

template <class T>
T little_endian_at(const char* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

}  // namespace

std::optional<Mesh> read_simple_ply(const std::string& path) {
  if constexpr (std::endian::native != std::endian::little) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::optional<PlyLayout> layout = simple_ply_layout(data);
  if (!layout || layout->faces == 0) return std::nullopt;
  Mesh mesh;
  mesh.vertices.resize(layout->vertices);
  const char* p = data.data() + layout->header_bytes;
  for (auto& v : mesh.vertices) {
    v = {little_endian_at<float>(p), little_endian_at<float>(p + 4),
         little_endian_at<float>(p + 8)};
    p += 12;
  }
  mesh.triangles.resize(layout->faces);
  for (auto& t : mesh.triangles) {
    if (static_cast<unsigned char>(*p) != 3) return std::nullopt;
    for (int k = 0; k < 3; ++k) {
      const auto index = little_endian_at<std::uint32_t>(p + 1 + 4 * k);
      if (index >= layout->vertices) return std::nullopt;  // negative ones too, as int
      t[k] = index;
    }
    p += 13;
  }
  return mesh;
}

namespace {

// Assimp's C API, loaded at the first mesh that needs it: most scenes never do (the workbench
// writes the direct layout), and loading Assimp with its own libraries at every start cost
// about 2 ms of a start-up of 25-40 (docs/BENCHMARKS.md, "Start-up").
struct AssimpApi {
  const aiScene* (*import_file)(const char*, unsigned) = nullptr;
  void (*release)(const aiScene*) = nullptr;
  const char* (*error)() = nullptr;
  std::string failure;  // why it could not be loaded; empty when loaded
};

const AssimpApi& assimp() {
  static AssimpApi api;
  static std::once_flag once;
  std::call_once(once, [] {
    void* lib = dlopen(LIGHTSOLVER_ASSIMP_SONAME, RTLD_NOW | RTLD_LOCAL);
    if (lib != nullptr) {
      api.import_file = reinterpret_cast<decltype(api.import_file)>(dlsym(lib, "aiImportFile"));
      api.release = reinterpret_cast<decltype(api.release)>(dlsym(lib, "aiReleaseImport"));
      api.error = reinterpret_cast<decltype(api.error)>(dlsym(lib, "aiGetErrorString"));
    }
    if (!api.import_file || !api.release || !api.error) {
      const char* why = dlerror();
      api.failure = std::string("the mesh library ") + LIGHTSOLVER_ASSIMP_SONAME +
                    " could not be loaded" + (why ? std::string(": ") + why : std::string());
    }
  });
  return api;
}

}  // namespace

Mesh read_mesh_with_assimp(const std::string& path) {
  const AssimpApi& api = assimp();
  if (!api.failure.empty()) throw InputError(path, "", "cannot read mesh: " + api.failure);
  // Only triangulation: no welding, smoothing or re-orientation, so winding and positions stay
  // exactly as written (the winding decides which side of a target is its front).
  const std::unique_ptr<const aiScene, void (*)(const aiScene*)> owned(
      api.import_file(path.c_str(), aiProcess_Triangulate), api.release);
  const aiScene* scene = owned.get();
  if (!scene || !scene->mRootNode) {
    throw InputError(path, "", std::string("cannot read mesh: ") + api.error());
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

}  // namespace lightsolver::detail

namespace lightsolver {

Mesh load_mesh_file(const std::string& path) {
  namespace fs = std::filesystem;
  if (!fs::is_regular_file(path)) throw InputError(path, "", "mesh file not found");
  const std::string ext = fs::path(path).extension().string();
  if (ext != ".ply" && ext != ".PLY" && ext != ".obj" && ext != ".OBJ") {
    throw InputError(path, "", "unsupported mesh format \"" + ext + "\" (use .ply or .obj)");
  }
  if (ext == ".ply" || ext == ".PLY") {
    if (std::optional<Mesh> mesh = detail::read_simple_ply(path)) return std::move(*mesh);
  }
  return detail::read_mesh_with_assimp(path);
}

}  // namespace lightsolver
