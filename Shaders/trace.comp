#version 460
// Photon tracer: one invocation traces paths first_path + i in a grid-stride loop (the dispatch
// is capped at 65535 groups), each exactly as the Embree backend does (embree_backend.cpp).
//
// Mesa's lavapipe ends every loop of a shader invocation once the invocation (8 SIMD lanes
// together) has run 65535 loop iterations in all (gallivm's LP_MAX_TGSI_LOOP_ITERATIONS): a
// path of hundreds of bounces would silently stop mid-flight. So before a path's deposits are
// added, a probe loop checks that the limit was never reached; if it was, the path's deposits
// are dropped and the path is queued to be traced again, alone in its workgroup (a fresh
// budget). A path that even alone needs more is counted as cut, and the results say so. Real
// GPUs have no such limit: the probe always passes.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#extension GL_EXT_control_flow_attributes : require

#include "trace_bindings.h"

layout(local_size_x_id = LS_SPEC_WORKGROUP_SIZE) in;

#define LS_SOBOL_PREFIX
#include "philox.glsl"
#include "sampling.glsl"
#include "trace_layout.glsl"
#include "sobol.glsl"
#include "bvh.glsl"
#include "instances.glsl"
#include "deposits.glsl"
#include "emit.glsl"
#include "scatter.glsl"

uint64_t g_segments = 0ul;
uint64_t g_capped = 0ul;
// Daylight photons from openings, those blocked outside, those blocked by glass (counters 4..6).
uint64_t g_opening[3] = uint64_t[3](0ul, 0ul, 0ul);

// A daylight photon from an opening (g_opening_push nonzero: emit_sky sets it for a portal,
// emit_sun_gpu for the sun, whose opening pushes along its beam) is absorbed at birth when its
// way out, against its direction, meets the scene (shared/luminaires.h, opening_escape_origin;
// the CPU's blocked_outside in embree_backend.cpp).
bool blocked_outside(vec3 o, vec3 d, bool first_pass) {
  if (!(HAS_SUN || HAS_SKY) || g_opening_push == vec3(0.0)) return false;
  const Hit h = trace_scene(opening_escape_origin(o, g_opening_push), -d);
  if (first_pass) {
    ++g_segments;
    ++g_opening[0];
  }
  if (h.tri == kNone) return false;
  if (first_pass) {
    ++g_opening[1];
    if (materials[meshes[tris[h.tri].mesh].material].type == kGlass) ++g_opening[2];
  }
  return true;
}

// One pass over the path. Statistics are counted on the first pass only.
void trace_path(uint64_t id, bool first_pass) {
  rng_init(pc.seed, id, pc.group);
  if (QUASI_RANDOM) rng_start_quasi_random(id);
  vec3 o, d;
  g_opening_push = vec3(0.0);
  emit(luminaires[pick_luminaire()], o, d);
  if (blocked_outside(o, d, first_pass)) return;
  for (uint bounce = 0u;; ++bounce) {
    const Hit h = trace_scene(o, d);
    if (first_pass) ++g_segments;
    if (HAS_GRIDS) cross_grids(o, d, h.t, bounce);
    if (h.tri == kNone) return;
    const MeshInfo mesh = meshes[tris[h.tri].mesh];
    const vec3 n = hit_normal(h);
    // Before the first scattering only without next-event estimation (pc.first_bounce 0) or
    // where it gave the target back to the photons, as continue_path in embree_backend.cpp.
    if (HAS_SURFACE_BINS && mesh.bin >= 0 &&
        (bounce >= pc.first_bounce || (mesh.flags & kMeshDirectByPhotons) != 0u) &&
        dot(d, n) < 0.0) {
      deposit(uint(mesh.bin));
    }
    if (!scatter(materials[mesh.material], n, d)) return;
    if (bounce >= pc.max_bounces) {
      if (first_pass) ++g_capped;  // still alive: its remaining light is lost (reported)
      return;
    }
    o = offset_ray_origin(world_hit_point(h), dot(d, n) > 0.0 ? n : -n);
  }
}

// True once lavapipe's loop limit has cut loops short: the probe's loop then stops early. Its
// bound and expected hash are push constants, so no compiler can fold the loop away.
bool loop_limit_reached() {
  uint h = 0u;
  for (uint i = 0u; i < pc.probe_iterations; ++i) h = h * 1664525u + 1013904223u;
  return h != pc.probe_hash;
}

// Traces path `offset` of this dispatch from deposit floor `floor_key` (0: from the start) and
// adds its deposits. Returns 0 when done, else 1 + the floor from which it must be traced again:
// its deposits since then were dropped because the loop limit cut the path short.
uint trace_whole_path(uint offset, uint floor_key) {
  bool first_pass = floor_key == 0u;
  for (;;) {  // one pass per iteration (see deposits.glsl)
    const uint64_t segments = g_segments, capped = g_capped;
    const uint64_t opening[3] = g_opening;
    deposits_begin(floor_key);
    trace_path(pc.first_path + uint64_t(offset), first_pass);
    if (loop_limit_reached()) {
      g_segments = segments;  // counted when the path is traced anew
      g_capped = capped;
      g_opening = opening;
      return floor_key + 1u;
    }
    floor_key = deposits_flush();  // loop-free (unrolled), so the limit cannot cut it
    if (floor_key == 0u) return 0u;
    first_pass = false;
  }
  return floor_key + 1u;  // only when the limit ended this loop between two passes
}

void main() {
  if (pc.retry != 0u) {
    if (gl_LocalInvocationIndex != 0u) return;  // one path per workgroup: alone in its lanes
    const uvec2 path = retry_paths[gl_WorkGroupID.x];
    if (trace_whole_path(path.x, path.y) != 0u) atomicAdd(counters[2], 1ul);  // cut for good
  } else {
    // The host gives each invocation at most one path (kPathsPerSubmit), so a limit reached
    // here cannot end this loop before a path it owns was traced.
    const uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
    for (uint i = gl_GlobalInvocationID.x; i < pc.path_count; i += stride) {
      const uint again = trace_whole_path(i, 0u);
      if (again != 0u) {
        retry_paths[atomicAdd(retry_dispatch[0], 1u)] = uvec2(i, again - 1u);
        atomicAdd(counters[3], 1ul);
      }
    }
  }
  if (g_segments != 0ul) atomicAdd(counters[0], g_segments);
  if (g_capped != 0ul) atomicAdd(counters[1], g_capped);
  for (uint k = 0u; k < 3u; ++k) {
    if (g_opening[k] != 0ul) atomicAdd(counters[4u + k], g_opening[k]);
  }
}
