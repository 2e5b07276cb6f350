#version 460
// Photon tracer: one invocation traces paths first_path + i in a grid-stride loop (the dispatch
// is capped at 65535 groups), each exactly as the Embree backend does (embree_backend.cpp).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require

layout(local_size_x_id = 0) in;

#include "philox.glsl"
#include "sampling.glsl"
#include "trace_layout.glsl"
#include "bvh.glsl"
#include "instances.glsl"
#include "deposits.glsl"
#include "emit.glsl"
#include "scatter.glsl"

uint64_t g_segments = 0ul;
uint64_t g_capped = 0ul;

// One pass over the path. Statistics are counted on the first pass only.
void trace_path(uint64_t id, bool first_pass) {
  rng_init(pc.seed, id);
  vec3 o, d;
  emit(luminaires[pick_luminaire()], o, d);
  for (uint bounce = 0u;; ++bounce) {
    const Hit h = trace_scene(o, d);
    if (first_pass) ++g_segments;
    if (HAS_GRIDS) cross_grids(o, d, h.t);
    if (h.tri == kNone) return;
    const MeshInfo mesh = meshes[tris[h.tri].mesh];
    const vec3 n = hit_normal(h);
    if (HAS_SURFACE_BINS && mesh.bin >= 0 && dot(d, n) < 0.0) deposit(uint(mesh.bin));
    if (!scatter(materials[mesh.material], n, d)) return;
    if (bounce >= pc.max_bounces) {
      if (first_pass) ++g_capped;  // still alive: its remaining light is lost (reported)
      return;
    }
    o = offset_ray_origin(world_hit_point(h), dot(d, n) > 0.0 ? n : -n);
  }
}

void main() {
  const uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint i = gl_GlobalInvocationID.x; i < pc.path_count; i += stride) {
    uint floor_key = 0u;
    bool first_pass = true;
    do {
      deposits_begin(floor_key);
      trace_path(pc.first_path + uint64_t(i), first_pass);
      floor_key = deposits_flush();
      first_pass = false;
    } while (floor_key != 0u);
  }
  if (g_segments != 0ul) atomicAdd(counters[0], g_segments);
  if (g_capped != 0ul) atomicAdd(counters[1], g_capped);
}
