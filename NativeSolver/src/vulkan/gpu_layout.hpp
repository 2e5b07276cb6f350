#pragma once
// C++ twins of the std430 structs in Shaders/scene_layout.glsl and Shaders/trace_layout.glsl.
// Every struct is a multiple of 16 bytes of 4-byte fields, so both sides agree byte for byte.
// Binding numbers and specialisation constant ids come from Shaders/trace_bindings.h, which the
// GLSL includes too; the tables at the end add the GLSL names. The luminaire record is not a
// twin: both sides compile the one in Shaders/shared/luminaires.h.
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <type_traits>

#include "shared/luminaires.h"  // Shaders/, on lightsolver_lib's public include path
#include "trace_bindings.h"     // Shaders/, on the include path of every target embedding shaders

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
  std::uint32_t flags;  ///< kMeshDirectByPhotons (PreparedMesh::direct_by_photons)
  std::uint32_t pad;
};
inline constexpr std::uint32_t kMeshDirectByPhotons = 1u;  ///< Shaders/trace_layout.glsl

struct Material {
  std::uint32_t type;     // Material::Type
  std::uint32_t p_first;  // 24-bit thresholds, see probability_threshold()
  std::uint32_t p_second;
  std::uint32_t thin;
  float ior, tau, alpha, pad;
};

/// A luminaire as trace.comp reads it: the shared record (Shaders/shared/luminaires.h).
using Luminaire = shared::LuminaireGpu;

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
  /// kGridIndirectOnly: an observer's tally (reflected light only); kGridDirectByPhotons:
  /// next-event groups' bounce-0 crossings count (PreparedGrid::direct_by_photons)
  std::uint32_t flags;
  float connect_r0;  ///< PreparedGrid::connect_r0: connected groups' near reflected crossings
  std::uint32_t pad[3];
};
inline constexpr std::uint32_t kGridIndirectOnly = 1u;     ///< Shaders/trace_layout.glsl
inline constexpr std::uint32_t kGridDirectByPhotons = 2u;  ///< Shaders/trace_layout.glsl

struct TracePush {
  std::uint64_t first_path;
  std::uint64_t seed;
  std::uint32_t path_count;
  std::uint32_t max_bounces;
  std::uint32_t luminaire_count;
  std::uint32_t grid_count;  // path_vertices.comp: the vertex buffer's capacity (no grids)
  std::uint32_t instance_count;
  std::uint32_t retry;             // 1: trace the paths queued in the retry list, one per group
  std::uint32_t probe_iterations;  // lavapipe's loop limit probe (trace.comp)
  std::uint32_t probe_hash;
  std::uint32_t group;            // luminaire group: photon stream, luminaires, tallies
  std::uint32_t luminaire_first;  // the group's luminaires: [first, first + luminaire_count)
  std::uint32_t tally_offset;     // group * bins
  std::uint32_t first_bounce;     // 1: no deposit at bounce 0 (PreparedGroup::next_event)
  std::uint32_t connected;        // 1: reflected crossings beyond connect_r0 left to the
                                  // connection (PreparedGroup::connect)
  std::uint32_t pad[3];
};

/// visibility.comp's push constants.
struct VisibilityPush {
  std::uint32_t ray_count;
  std::uint32_t instance_count;
  std::uint32_t retry;  // 1: trace the queued rays, one per workgroup
  std::uint32_t probe_iterations;
  std::uint32_t probe_hash;
  std::uint32_t pad[3];
};

/// One diffuse vertex as path_vertices.comp writes it (the host makes a PathVertex of it).
struct PathVertexGpu {
  float origin[3];
  std::uint32_t material;
  float normal[3];
  std::uint32_t path;    // offset in the dispatch
  std::uint32_t vertex;  // 1, 2, ... along the path
  std::uint32_t pass;    // 0, or 1 for a path traced again (lavapipe's loop limit)
  std::uint32_t pad[2];
};
static_assert(sizeof(PathVertexGpu) == 48);

static_assert(sizeof(Node) == 64 && sizeof(Tri) == 48 && sizeof(MeshInfo) == 16);
static_assert(sizeof(Material) == 32 && sizeof(Luminaire) == 80 && sizeof(Grid) == 80);
static_assert(sizeof(Photometric) == 96 && sizeof(Instance) == 160);
static_assert(sizeof(TracePush) == 80 && sizeof(VisibilityPush) == 32);
// The shared record in C++ (glm::vec3 is three packed floats) at std430's offsets in GLSL, where
// a vec3 is 16-byte aligned and the 4-byte field after it fills its last word.
static_assert(std::is_trivially_copyable_v<Luminaire> && alignof(Luminaire) == 4);
static_assert(offsetof(Luminaire, position) == 0 && offsetof(Luminaire, type) == 12 &&
              offsetof(Luminaire, axis) == 16 && offsetof(Luminaire, half_beam_rad) == 28 &&
              offsetof(Luminaire, corner) == 32 && offsetof(Luminaire, half_field_rad) == 44 &&
              offsetof(Luminaire, edge1) == 48 && offsetof(Luminaire, cos_half_field) == 60 &&
              offsetof(Luminaire, edge2) == 64 && offsetof(Luminaire, photometric) == 76);

/// The number of luminaire types the GPU has (entries of LS_LUMINAIRE_TYPES).
#define LS_COUNT_TYPE(name, code, has, emission) +1
inline constexpr std::uint32_t kGpuLuminaireTypeCount = 0 LS_LUMINAIRE_TYPES(LS_COUNT_TYPE);
#undef LS_COUNT_TYPE

/// Specialisation constant ids of trace.comp; the numbers come from Shaders/trace_bindings.h.
/// The luminaire types' switches follow kFirstLuminaireSwitch, one per code (luminaire_switch).
enum SpecId : std::uint32_t {
  kWorkgroupSize = LS_SPEC_WORKGROUP_SIZE,
  kHasDiffuse = LS_SPEC_HAS_DIFFUSE,
  kHasMirror = LS_SPEC_HAS_MIRROR,
  kHasGlass = LS_SPEC_HAS_GLASS,
  kHasGlossy = LS_SPEC_HAS_GLOSSY,
  kHasGrids = LS_SPEC_HAS_GRIDS,
  kHasSurfaceBins = LS_SPEC_HAS_SURFACE_BINS,
  kManyLuminaires = LS_SPEC_MANY_LUMINAIRES,
  kHasInstances = LS_SPEC_HAS_INSTANCES,
  kQuasiRandom = LS_SPEC_QUASI_RANDOM,
  kFirstLuminaireSwitch = LS_SPEC_FIRST_LUMINAIRE,
  kSpecCount = LS_SPEC_FIRST_LUMINAIRE + kGpuLuminaireTypeCount
};

/// The switch of the luminaire type with GPU code `code` (its HAS_* constant).
constexpr SpecId luminaire_switch(std::uint32_t code) {
  return static_cast<SpecId>(kFirstLuminaireSwitch + code);
}

/// Storage-buffer bindings (descriptor set 0) of trace.comp; the numbers come from
/// Shaders/trace_bindings.h.
enum Binding : std::uint32_t {
  kNodes = LS_BINDING_NODES,
  kTris = LS_BINDING_TRIS,
  kTriNormals = LS_BINDING_TRI_NORMALS,
  kMeshes = LS_BINDING_MESHES,
  kMaterials = LS_BINDING_MATERIALS,
  kLuminaires = LS_BINDING_LUMINAIRES,
  kLuminaireCdf = LS_BINDING_LUMINAIRE_CDF,
  kGrids = LS_BINDING_GRIDS,
  kTallies = LS_BINDING_TALLIES,
  kCounters = LS_BINDING_COUNTERS,
  kPhotometrics = LS_BINDING_PHOTOMETRICS,
  kPhotoFloats = LS_BINDING_PHOTO_FLOATS,
  kPhotoCdf = LS_BINDING_PHOTO_CDF,
  kInstances = LS_BINDING_INSTANCES,
  kRetry = LS_BINDING_RETRY,
  kSobol = LS_BINDING_SOBOL,
  kBindingCount = LS_BINDING_COUNT
};

/// visibility.comp's own bindings, after trace.comp's (whose geometry and instances it reads at
/// the same numbers).
enum VisibilityBinding : std::uint32_t {
  kShadowRays = LS_BINDING_SHADOW_RAYS,
  kVisible = LS_BINDING_VISIBLE,
  kVisRetry = LS_BINDING_VIS_RETRY,
  kVisibilityBindingCount = LS_VISIBILITY_BINDING_COUNT
};
static_assert(std::uint32_t(kShadowRays) == std::uint32_t(kBindingCount) &&
              kVisibilityBindingCount == kVisRetry + 1);

/// path_vertices.comp's own bindings, after trace.comp's (all of whose buffers it binds).
enum PathBinding : std::uint32_t {
  kPathVertices = LS_BINDING_PATH_VERTICES,
  kPathControl = LS_BINDING_PATH_CONTROL,
  kPathBindingCount = LS_PATH_BINDING_COUNT
};
static_assert(std::uint32_t(kPathVertices) == std::uint32_t(kBindingCount) &&
              kPathBindingCount == kPathControl + 1);

/// A storage buffer of trace.comp: its binding, the GLSL block bound there and the name that
/// errors use.
struct BufferInfo {
  Binding binding;
  const char* block;
  const char* label;
};

/// Every buffer, in binding order: the backend creates its buffers from this table (the
/// descriptor set binds row i at binding i), and bindings_test checks the compiled shader's
/// bindings and block names against it.
inline constexpr BufferInfo kBuffers[] = {
    {kNodes, "Nodes", "BVH nodes"},
    {kTris, "Tris", "triangles"},
    {kTriNormals, "TriNormals", "triangle normals"},
    {kMeshes, "Meshes", "meshes"},
    {kMaterials, "Materials", "materials"},
    {kLuminaires, "Luminaires", "luminaires"},
    {kLuminaireCdf, "LuminaireCdf", "luminaire CDF"},
    {kGrids, "Grids", "grids"},
    {kTallies, "Tallies", "tallies"},
    {kCounters, "Counters", "counters"},
    {kPhotometrics, "Photometrics", "photometric luminaires"},
    {kPhotoFloats, "PhotoFloats", "photometric tables"},
    {kPhotoCdf, "PhotoCdf", "photometric CDF"},
    {kInstances, "Instances", "instances"},
    {kRetry, "Retry", "retry list"},
    {kSobol, "SobolDirections", "Sobol' directions"},
};

/// A specialisation constant of trace.comp and its GLSL name (the workgroup size has none in
/// SPIR-V: it is the x of the WorkgroupSize built-in).
struct SpecInfo {
  SpecId id;
  const char* name;
};

/// Every specialisation constant, in id order (checked against the shader by bindings_test); the
/// luminaire types' rows are generated from their list.
// Unformatted: clang-format would indent the rows under the brace for the #define among them.
// clang-format off
inline constexpr SpecInfo kSpecConstants[] = {
    {kWorkgroupSize, "local_size_x"},
    {kHasDiffuse, "HAS_DIFFUSE"},
    {kHasMirror, "HAS_MIRROR"},
    {kHasGlass, "HAS_GLASS"},
    {kHasGlossy, "HAS_GLOSSY"},
    {kHasGrids, "HAS_GRIDS"},
    {kHasSurfaceBins, "HAS_SURFACE_BINS"},
    {kManyLuminaires, "MANY_LUMINAIRES"},
    {kHasInstances, "HAS_INSTANCES"},
    {kQuasiRandom, "QUASI_RANDOM"},
#define LS_SPEC_ROW(name, code, has, emission) {luminaire_switch(code), #has},
    LS_LUMINAIRE_TYPES(LS_SPEC_ROW)
#undef LS_SPEC_ROW
};
// clang-format on

// Row i must be number i: no gap, no duplicate, no row missing (trace_bindings.h numbers them
// 0..count-1, and the descriptor set layout binds buffers_[i] at binding i). For the luminaire
// switches this holds LS_LUMINAIRE_TYPES's codes to 0, 1, 2, ... in order.
constexpr bool numbered_in_order() {
  for (std::uint32_t i = 0; i < std::size(kBuffers); ++i) {
    if (kBuffers[i].binding != i) return false;
  }
  for (std::uint32_t i = 0; i < std::size(kSpecConstants); ++i) {
    if (kSpecConstants[i].id != i) return false;
  }
  return true;
}
static_assert(std::size(kBuffers) == kBindingCount && std::size(kSpecConstants) == kSpecCount);
static_assert(numbered_in_order(), "kBuffers / kSpecConstants must list 0, 1, 2, ... in order");

}  // namespace lightsolver::detail::gpu
