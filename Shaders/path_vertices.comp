#version 460
// Backend::path_vertices (model/backend.hpp) on the device: the diffuse vertices of paths
// pc.first_path + i, each traced as the Embree backend's trace_vertices (embree_backend.cpp):
// emitted as trace.comp emits (stream pc.group, Philox only), absorbed at birth when blocked
// outside, then at each hit up to max_bounces a vertex when the material is diffuse (else the
// path ends) and a diffuse scattering. Nothing is deposited: a separate, small pipeline, made
// only when path_vertices is first called, so the trace pipeline's compile time is untouched.
//
// Vertices are appended in any order with their path, index and pass; the host sorts them.
// Lavapipe's loop limit (top of trace.comp): one path per invocation; a path whose probe fails
// is queued and traced again alone in its workgroup (pass 1); the host drops its pass-0
// vertices. A path still cut then is counted, and the host refuses the chunk.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

#include "trace_bindings.h"

layout(local_size_x_id = LS_SPEC_WORKGROUP_SIZE) in;

#include "philox.glsl"
#include "sampling.glsl"
#include "trace_layout.glsl"
#include "bvh.glsl"
#include "instances.glsl"
#include "emit.glsl"
#include "scatter.glsl"

// C++ twin: gpu::PathVertexGpu (NativeSolver/src/vulkan/gpu_layout.hpp), 48 bytes.
struct PathVertexGpu {
  vec3 origin; uint material;
  vec3 normal; uint path;    // the photon's offset in this dispatch
  uint vertex; uint pass; uint pad0, pad1;
};
layout(std430, set = 0, binding = LS_BINDING_PATH_VERTICES) writeonly buffer PathVertices {
  PathVertexGpu path_vertices[];
};
// [0..3]: the retry pass's VkDispatchIndirectCommand {x, 1, 1} and a pad; [4]: vertices
// appended (may exceed the capacity: the host then traces the chunk in smaller parts); [5]:
// paths cut for good; [6], [7]: pad; then the queued paths' offsets.
layout(std430, set = 0, binding = LS_BINDING_PATH_CONTROL) buffer PathControl {
  uint control[8];
  uint retry_list[];
};

bool loop_limit_reached() {
  uint h = 0u;
  for (uint i = 0u; i < pc.probe_iterations; ++i) h = h * 1664525u + 1013904223u;
  return h != pc.probe_hash;
}

void append(vec3 o, uint material, vec3 n, uint path, uint vertex, uint pass) {
  const uint slot = atomicAdd(control[4], 1u);
  if (slot < pc.grid_count) {  // grid_count: the buffer's capacity in vertices
    path_vertices[slot] = PathVertexGpu(o, material, n, path, vertex, pass, 0u, 0u);
  }
}

void trace_vertices(uint offset, uint pass) {
  rng_init(pc.seed, pc.first_path + uint64_t(offset), pc.group);
  vec3 o, d;
  g_opening_push = vec3(0.0);
  emit(luminaires[pick_luminaire()], o, d);
  if ((HAS_SUN || HAS_SKY) && g_opening_push != vec3(0.0) &&
      trace_scene(opening_escape_origin(o, g_opening_push), -d).tri != kNone) {
    return;  // blocked outside (trace.comp's blocked_outside)
  }
  for (uint vertex = 1u; vertex <= pc.max_bounces; ++vertex) {
    const Hit h = trace_scene(o, d);
    if (h.tri == kNone) return;
    const uint material = meshes[tris[h.tri].mesh].material;
    const MaterialGpu m = materials[material];
    if (m.type != kDiffuse) return;  // and reflectance 0: the host drops it (never survives)
    const vec3 n = hit_normal(h);
    const vec3 facing = dot(d, n) < 0.0 ? n : -n;
    o = offset_ray_origin(world_hit_point(h), facing);
    append(o, material, facing, offset, vertex, pass);
    if (rng_u24() >= m.p_first) return;
    d = sample_cosine(facing);
  }
}

void main() {
  if (pc.retry != 0u) {
    if (gl_LocalInvocationIndex != 0u) return;  // one path per workgroup: alone in its lanes
    trace_vertices(retry_list[gl_WorkGroupID.x], 1u);
    if (loop_limit_reached()) atomicAdd(control[5], 1u);
    return;
  }
  const uint i = gl_GlobalInvocationID.x;
  if (i >= pc.path_count) return;
  trace_vertices(i, 0u);
  if (!loop_limit_reached()) return;
  retry_list[atomicAdd(control[0], 1u)] = i;
}
