#pragma once
// C++ twins of the std430 structs in Shaders/scene_layout.glsl and Shaders/trace_layout.glsl.
// Every struct is a multiple of 16 bytes of 4-byte fields, so both sides agree byte for byte.
#include <cstdint>

namespace lightsolver::detail::gpu {

constexpr std::uint32_t kNone = 0xFFFFFFFFu;

struct Node {  // binary BVH node with both children's boxes
  float lo0[3];
  std::uint32_t child0;
  float hi0[3];
  std::uint32_t count0;  // 0: child0 is a node; > 0: child0 is the first of count0 triangles
  float lo1[3];
  std::uint32_t child1;
  float hi1[3];
  std::uint32_t count1;
};

struct Tri {  // triangle in leaf order
  float v0[3];
  std::uint32_t mesh;
  float v1[3];
  std::uint32_t prim;
  float v2[3];
  std::uint32_t pad;
};

struct MeshInfo {
  std::uint32_t material;
  std::int32_t bin;
  std::uint32_t pad[2];
};

struct Material {
  std::uint32_t type;     // Material::Type
  std::uint32_t p_first;  // 24-bit thresholds, see probability_threshold()
  std::uint32_t p_second;
  std::uint32_t thin;
  float ior, tau, alpha, pad;
};

struct Luminaire {
  float position[3];
  std::uint32_t type;  // Luminaire::Type
  float axis[3];
  float half_beam;
  float corner[3];
  float half_field;
  float edge1[3];
  float cos_half_field;
  float edge2[3];
  std::uint32_t photometric;  // index into the Photometric records (photometric type only)
};

struct Photometric {  // one photometric luminaire's sampler tables, as offsets
  float pole[3];
  std::uint32_t plane_off;  // into the photometric floats
  float zero[3];
  std::uint32_t np;
  float ninety[3];
  std::uint32_t polar_off;
  float c0[3];
  std::uint32_t nt;
  std::uint32_t candela_off, bound_off;  // into the photometric floats
  std::uint32_t cell_off, cell_count;    // into the photometric CDF thresholds
  std::uint32_t last_cell, round_opening;
  float length, width;
};

struct Instance {       // a movable mesh's BVH placed in the world
  float to_world[16];   // column-major, as glm::mat4
  float to_object[16];  // inverse of to_world
  float lo[3];
  std::uint32_t root;  // root node of the mesh's own BVH
  float hi[3];
  std::uint32_t pad;
};

struct Grid {
  float corner[3];
  std::uint32_t nu;
  float normal[3];
  std::uint32_t nv;
  float du[3];
  std::uint32_t bin;
  float dv[3];
  std::uint32_t pad;
};

struct TracePush {
  std::uint64_t first_path;
  std::uint64_t seed;
  std::uint32_t path_count;
  std::uint32_t max_bounces;
  std::uint32_t luminaire_count;
  std::uint32_t grid_count;
  std::uint32_t instance_count;
  std::uint32_t retry;             // 1: trace the paths queued in the retry list, one per group
  std::uint32_t probe_iterations;  // lavapipe's loop limit probe (trace.comp)
  std::uint32_t probe_hash;
  std::uint32_t pad;
};

static_assert(sizeof(Node) == 64 && sizeof(Tri) == 48 && sizeof(MeshInfo) == 16);
static_assert(sizeof(Material) == 32 && sizeof(Luminaire) == 80 && sizeof(Grid) == 64);
static_assert(sizeof(Photometric) == 96 && sizeof(Instance) == 160);
static_assert(sizeof(TracePush) == 56);

/// Specialisation constant ids of trace.comp (0 is the workgroup size).
enum SpecId : std::uint32_t {
  kWorkgroupSize = 0,
  kHasDiffuse,
  kHasMirror,
  kHasGlass,
  kHasGlossy,
  kHasPoint,
  kHasSpot,
  kHasArea,
  kHasDirectional,
  kHasGrids,
  kHasSurfaceBins,
  kManyLuminaires,
  kHasPhotometric,
  kHasInstances,
  kSpecCount
};

/// Bindings of trace.comp, in order.
enum Binding : std::uint32_t {
  kNodes,
  kTris,
  kTriNormals,
  kMeshes,
  kMaterials,
  kLuminaires,
  kLuminaireCdf,
  kGrids,
  kTallies,
  kCounters,
  kPhotometrics,
  kPhotoFloats,
  kPhotoCdf,
  kInstances,
  kRetry,
  kBindingCount
};

}  // namespace lightsolver::detail::gpu
