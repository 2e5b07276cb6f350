#version 460
// Test kernel: closest hit of arbitrary rays through the GPU BVH, for comparison with Embree.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

layout(local_size_x = 64) in;

#include "philox.glsl"  // sampling.glsl draws from it
#include "sampling.glsl"
#include "bvh.glsl"

struct RayIn { vec4 origin; vec4 dir; };
struct HitOut { float t; uint mesh; uint prim; uint hit; };

layout(std430, set = 0, binding = 3) readonly buffer Rays { RayIn rays[]; };
layout(std430, set = 0, binding = 4) writeonly buffer Hits { HitOut hits[]; };

layout(push_constant) uniform Push { uint ray_count; } pc;

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= pc.ray_count) return;
  const Hit h = trace_closest(rays[i].origin.xyz, rays[i].dir.xyz);
  HitOut o;
  o.hit = h.tri == kNone ? 0u : 1u;
  o.t = h.t;
  o.mesh = h.tri == kNone ? kNone : tris[h.tri].mesh;
  o.prim = h.tri == kNone ? kNone : tris[h.tri].prim;
  hits[i] = o;
}
