// Bindings, push constants and specialisation constants of trace.comp. Structs and push
// constants must match NativeSolver/src/vulkan/gpu_layout.hpp (sizes asserted there); binding
// numbers and constant ids come from trace_bindings.h, which the C++ side includes too, and the
// luminaire record and types from shared/luminaires.h, which it includes as well.
#ifndef LIGHTSOLVER_TRACE_LAYOUT_GLSL
#define LIGHTSOLVER_TRACE_LAYOUT_GLSL

#include "instance_layout.glsl"  // movable meshes: HAS_INSTANCES, instances[]
#include "scene_layout.glsl"
#include "shared/luminaires.h"
#include "trace_bindings.h"

// Feature switches: the pipeline is specialised per scene so that a scene only pays for the
// materials, luminaires and targets it contains (dead branches are removed by the driver).
layout(constant_id = LS_SPEC_HAS_DIFFUSE) const bool HAS_DIFFUSE = true;
layout(constant_id = LS_SPEC_HAS_MIRROR) const bool HAS_MIRROR = true;
layout(constant_id = LS_SPEC_HAS_GLASS) const bool HAS_GLASS = true;
layout(constant_id = LS_SPEC_HAS_GLOSSY) const bool HAS_GLOSSY = true;
layout(constant_id = LS_SPEC_HAS_GRIDS) const bool HAS_GRIDS = true;
layout(constant_id = LS_SPEC_HAS_SURFACE_BINS) const bool HAS_SURFACE_BINS = true;
layout(constant_id = LS_SPEC_MANY_LUMINAIRES) const bool MANY_LUMINAIRES = true;
// Sampler "sobol": a path's first draws are its scrambled Sobol' point (sobol.glsl). A constant,
// not a push constant, so the pipelines of random runs compile without that code.
layout(constant_id = LS_SPEC_QUASI_RANDOM) const bool QUASI_RANDOM = false;
// One per luminaire type (HAS_POINT ...), keeping its branch of emit() (emit.glsl).
#define LS_LUMINAIRE_SWITCH(name, code, has, emission) \
  layout(constant_id = LS_SPEC_FIRST_LUMINAIRE + code) const bool has = true;
LS_LUMINAIRE_TYPES(LS_LUMINAIRE_SWITCH)
#undef LS_LUMINAIRE_SWITCH

const uint kDiffuse = LS_MATERIAL_DIFFUSE, kMirror = LS_MATERIAL_MIRROR;
const uint kGlass = LS_MATERIAL_GLASS, kGlossy = LS_MATERIAL_GLOSSY;

struct MeshInfo {
  uint material;
  int bin;  // surface-target bin or -1
  uint flags;  // kMeshDirectByPhotons: next-event groups' bounce-0 hits deposit too
  uint pad0;
};
const uint kMeshDirectByPhotons = 1u;

// Probabilities as 24-bit integer thresholds: survive/choose when rng_u24() < threshold, which is
// exactly the CPU's `uniform() < p` for the double p.
struct MaterialGpu {
  uint type;
  uint p_first;   // diffuse/mirror: reflectance; glossy: reflectance
  uint p_second;  // glossy: reflectance + specular
  uint thin;
  float ior, tau, alpha, pad;
};

// A photometric luminaire's sampler (lightsolver::SamplerTables): offsets into photo_floats[]
// (plane and polar nodes in degrees, candela grid, per-cell rejection bound) and photo_cdf53[].
struct PhotoGpu {
  vec3 pole; uint plane_off;
  vec3 zero; uint np;
  vec3 ninety; uint polar_off;
  vec3 c0; uint nt;
  uint candela_off, bound_off, cell_off, cell_count;
  uint last_cell;      // the last cell with flux: taken when the draw rounds up to the total
  uint round_opening;  // elliptical opening (else rectangular)
  float open_length, open_width;  // opening extents along x (C0) and y (C90)
};

struct GridGpu {
  vec3 corner; uint nu;
  vec3 normal; uint nv;
  vec3 du; uint bin;
  vec3 dv; uint flags;  // bit 0 (kGridIndirectOnly): count reflected light only (observers);
                        // bit 1 (kGridDirectByPhotons): next-event groups' bounce 0 counts
  float connect_r0;     // connected groups count reflected crossings only this near (0: all)
  uint pad0, pad1, pad2;
};
const uint kGridIndirectOnly = 1u, kGridDirectByPhotons = 2u;

layout(std430, set = 0, binding = LS_BINDING_MESHES) readonly buffer Meshes { MeshInfo meshes[]; };
layout(std430, set = 0, binding = LS_BINDING_MATERIALS) readonly buffer Materials {
  MaterialGpu materials[];
};
layout(std430, set = 0, binding = LS_BINDING_LUMINAIRES) readonly buffer Luminaires {
  LuminaireGpu luminaires[];
};
// ceil(cdf * 2^53): luminaire i is chosen for the first i with rng_u53() < cdf53[i].
layout(std430, set = 0, binding = LS_BINDING_LUMINAIRE_CDF) readonly buffer LuminaireCdf {
  uint64_t cdf53[];
};
layout(std430, set = 0, binding = LS_BINDING_GRIDS) readonly buffer Grids { GridGpu grids[]; };
layout(std430, set = 0, binding = LS_BINDING_TALLIES) buffer Tallies {
  uint64_t tallies[];  // S, Q per bin
};
// Ray segments, paths capped at max_bounces, paths cut short for good by the device's loop limit,
// paths queued to be traced again (trace.comp).
layout(std430, set = 0, binding = LS_BINDING_COUNTERS) buffer Counters { uint64_t counters[]; };
layout(std430, set = 0, binding = LS_BINDING_PHOTOMETRICS) readonly buffer Photometrics {
  PhotoGpu photometrics[];
};
layout(std430, set = 0, binding = LS_BINDING_PHOTO_FLOATS) readonly buffer PhotoFloats {
  float photo_floats[];
};
// ceil-type 53-bit thresholds: cell c is chosen for the first c with rng_u53() < photo_cdf53[c].
layout(std430, set = 0, binding = LS_BINDING_PHOTO_CDF) readonly buffer PhotoCdf {
  uint64_t photo_cdf53[];
};
// Paths to trace again, each alone in its workgroup (see trace.comp): the first three words are
// the VkDispatchIndirectCommand of that retry dispatch, then (path offset, deposit floor) pairs.
layout(std430, set = 0, binding = LS_BINDING_RETRY) buffer Retry {
  uint retry_dispatch[4];
  uvec2 retry_paths[];
};
// Sobol' direction numbers, bit-reversed (lightsolver::detail::sobol_directions()): row j holds
// index bit j's numbers of coordinates 4q .. 4q + 3 at j * 4 + q.
layout(std430, set = 0, binding = LS_BINDING_SOBOL) readonly buffer SobolDirections {
  uvec4 sobol_directions[];
};

layout(push_constant) uniform Push {
  uint64_t first_path;
  uint64_t seed;
  uint path_count;
  uint max_bounces;
  uint luminaire_count;
  uint grid_count;
  uint instance_count;
  uint retry;             // 1: trace the paths listed in Retry, one per workgroup
  uint probe_iterations;  // loop_limit_reached(): iterations of the probe loop ...
  uint probe_hash;        // ... and the hash they give when every one of them ran
  uint group;             // the luminaire group: its photon stream (rng_init) ...
  uint luminaire_first;   // ... its luminaires: [first, first + luminaire_count) ...
  uint tally_offset;      // ... and its tallies: group * bins
  uint first_bounce;      // 1: the group's direct light is by next-event estimation: no
                          // deposit before the first scattering (bounce 0)
  uint connected;         // 1: the group's far reflected light at grids is by connection
                          // (PreparedGroup::connect): reflected crossings beyond connect_r0
                          // are left to it (deposits.glsl, cross_grids)
  uint pad0, pad1, pad2;
} pc;

#endif
