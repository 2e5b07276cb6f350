// Bindings, push constants and specialisation constants of trace.comp. Must match
// NativeSolver/src/vulkan/gpu_layout.hpp.
#ifndef LIGHTSOLVER_TRACE_LAYOUT_GLSL
#define LIGHTSOLVER_TRACE_LAYOUT_GLSL

#include "scene_layout.glsl"

// Feature switches: the pipeline is specialised per scene so that a scene only pays for the
// materials, luminaires and targets it contains (dead branches are removed by the driver).
layout(constant_id = 1) const bool HAS_DIFFUSE = true;
layout(constant_id = 2) const bool HAS_MIRROR = true;
layout(constant_id = 3) const bool HAS_GLASS = true;
layout(constant_id = 4) const bool HAS_GLOSSY = true;
layout(constant_id = 5) const bool HAS_POINT = true;
layout(constant_id = 6) const bool HAS_SPOT = true;
layout(constant_id = 7) const bool HAS_AREA = true;
layout(constant_id = 8) const bool HAS_DIRECTIONAL = true;
layout(constant_id = 9) const bool HAS_GRIDS = true;
layout(constant_id = 10) const bool HAS_SURFACE_BINS = true;
layout(constant_id = 11) const bool MANY_LUMINAIRES = true;

const uint kDiffuse = 0u, kMirror = 1u, kGlass = 2u, kGlossy = 3u;          // Material::Type
const uint kPoint = 0u, kSpot = 1u, kArea = 2u, kDirectional = 3u;           // Luminaire::Type

struct MeshInfo {
  uint material;
  int bin;  // surface-target bin or -1
  uint pad0, pad1;
};

// Probabilities as 24-bit integer thresholds: survive/choose when rng_u24() < threshold, which is
// exactly the CPU's `uniform() < p` for the double p.
struct MaterialGpu {
  uint type;
  uint p_first;   // diffuse/mirror: reflectance; glossy: reflectance
  uint p_second;  // glossy: reflectance + specular
  uint thin;
  float ior, tau, alpha, pad;
};

struct LuminaireGpu {
  vec3 position; uint type;
  vec3 axis; float half_beam;
  vec3 corner; float half_field;
  vec3 edge1; float cos_half_field;
  vec3 edge2; float pad;
};

struct GridGpu {
  vec3 corner; uint nu;
  vec3 normal; uint nv;
  vec3 du; uint bin;
  vec3 dv; uint pad;
};

layout(std430, set = 0, binding = 3) readonly buffer Meshes { MeshInfo meshes[]; };
layout(std430, set = 0, binding = 4) readonly buffer Materials { MaterialGpu materials[]; };
layout(std430, set = 0, binding = 5) readonly buffer Luminaires { LuminaireGpu luminaires[]; };
// ceil(cdf * 2^53): luminaire i is chosen for the first i with rng_u53() < cdf53[i].
layout(std430, set = 0, binding = 6) readonly buffer LuminaireCdf { uint64_t cdf53[]; };
layout(std430, set = 0, binding = 7) readonly buffer Grids { GridGpu grids[]; };
layout(std430, set = 0, binding = 8) buffer Tallies { uint64_t tallies[]; };  // S, Q per bin
layout(std430, set = 0, binding = 9) buffer Counters { uint64_t counters[]; };  // segments, capped

layout(push_constant) uniform Push {
  uint64_t first_path;
  uint64_t seed;
  uint path_count;
  uint max_bounces;
  uint luminaire_count;
  uint grid_count;
} pc;

#endif
