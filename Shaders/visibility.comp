#version 460
// Shadow rays of next-event estimation (Backend::visible, model/backend.hpp): visible[i] = 1 when
// nothing of the scene (static BVH and movable meshes at their current transforms; every
// triangle opaque, glass and mirrors included) lies on origin + t * direction for 0 < t < t_max,
// else 0. Virtual grids are not geometry: they are not even bound here. The traversal is
// bvh.glsl's and instances.glsl's with LS_ANY_HIT: it stops at the first hit nearer than t_max.
//
// Lavapipe's loop limit (see the top of trace.comp): each invocation owns exactly one ray (no
// grid-stride loop), so a limit reached cuts only the traversals of the rays of those 8 lanes.
// A cut traversal that found a hit is right (the hit is real); one that found none is unknown:
// it is written as kCut and queued, and the retry pass (pc.retry = 1) traces each queued ray
// alone in its workgroup, with the whole limit to itself. A ray still cut then stays kCut, and
// the host refuses the batch (never a wrong answer). Real GPUs have no limit: nothing is queued.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

#include "trace_bindings.h"

layout(local_size_x_id = LS_SPEC_WORKGROUP_SIZE) in;

#define LS_ANY_HIT 1
#include "philox.glsl"  // sampling.glsl draws from it
#include "sampling.glsl"
#include "instance_layout.glsl"
#include "scene_layout.glsl"
#include "bvh.glsl"

// C++ twin: gpu::VisibilityPush (NativeSolver/src/vulkan/gpu_layout.hpp).
layout(push_constant) uniform Push {
  uint ray_count;         // rays in this chunk
  uint instance_count;    // movable meshes
  uint retry;             // 1: trace the rays queued in VisRetry, one per workgroup
  uint probe_iterations;  // loop_limit_reached(): iterations of the probe loop ...
  uint probe_hash;        // ... and the hash they give when every one of them ran
  uint pad0, pad1, pad2;
} pc;

#include "instances.glsl"

// C++ twin: ShadowRay (model/backend.hpp), 32 bytes.
struct ShadowRay {
  vec3 origin; float t_max;
  vec3 direction; float pad;
};

const uint kCut = 2u;  // not known: the loop limit cut the traversal short before any hit

layout(std430, set = 0, binding = LS_BINDING_SHADOW_RAYS) readonly buffer ShadowRays {
  ShadowRay rays[];
};
layout(std430, set = 0, binding = LS_BINDING_VISIBLE) writeonly buffer Visible {
  uint visible[];  // 1 visible, 0 blocked, kCut unknown
};
// The VkDispatchIndirectCommand of the retry pass (x: one workgroup per queued ray), the queue's
// length, then the queue.
layout(std430, set = 0, binding = LS_BINDING_VIS_RETRY) buffer VisRetry {
  uint retry_dispatch[4];
  uint retry_rays[];
};

// True once lavapipe's loop limit has cut loops short (trace.comp's probe).
bool loop_limit_reached() {
  uint h = 0u;
  for (uint i = 0u; i < pc.probe_iterations; ++i) h = h * 1664525u + 1013904223u;
  return h != pc.probe_hash;
}

// 1 visible, 0 blocked, kCut when the limit may have hidden a blocker.
uint shadow(uint i) {
  const ShadowRay r = rays[i];
  const Hit h = trace_scene_within(r.origin, r.direction, r.t_max);
  if (h.tri != kNone) return 0u;
  return loop_limit_reached() ? kCut : 1u;
}

void main() {
  if (pc.retry != 0u) {
    if (gl_LocalInvocationIndex != 0u) return;  // one ray per workgroup: alone in its lanes
    const uint i = retry_rays[gl_WorkGroupID.x];
    visible[i] = shadow(i);
    return;
  }
  const uint i = gl_GlobalInvocationID.x;
  if (i >= pc.ray_count) return;
  const uint v = shadow(i);
  visible[i] = v;
  if (v != kCut) return;
  // Queued; the retry pass has at most 65535 workgroups (the least maxComputeWorkGroupCount[0]
  // any device has): a ray beyond stays kCut, and the host refuses the batch.
  const uint slot = atomicAdd(retry_dispatch[3], 1u);
  if (slot >= 65535u) return;
  retry_rays[slot] = i;
  atomicMax(retry_dispatch[0], slot + 1u);
}
