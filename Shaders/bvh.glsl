// Closest-hit BVH traversal with the watertight ray/triangle test of Woop, Benthin & Wald
// (JCGT 2013): vertices are sheared into ray space so a shared edge gives the same edge function,
// exactly negated, in both triangles; `precise` forbids FMA contraction, which would break that
// symmetry. A ray through an edge (edge function exactly 0) therefore hits at least one of the
// two triangles and closed rooms do not leak. Box tests widen the far distance by 2*gamma(3)
// (Ize 2013) so rounding never culls a box the ray touches.
#ifndef LIGHTSOLVER_BVH_GLSL
#define LIGHTSOLVER_BVH_GLSL

#include "scene_layout.glsl"

const float kNoHit = 3.402823466e38;  // FLT_MAX: t of a miss
const int kStackSize = 64;            // the CPU builder caps depth at 48

struct Hit {
  float t;
  uint tri;  // leaf-order triangle, kNone on a miss
  float u, v;  // barycentric weights of v1 and v2 (Embree's convention)
  uint inst;   // instance (movable mesh) hit, kNone for static geometry
};

struct RayPre {
  vec3 o, inv_d;
  int kx, ky, kz;
  vec3 shear;  // Sx, Sy, Sz
};

RayPre prepare_ray(vec3 o, vec3 d) {
  RayPre r;
  r.o = o;
  // Replacing 0 by a tiny value keeps slab distances finite and NaN-free.
  const vec3 safe = mix(d, vec3(copysign_one(d.x), copysign_one(d.y), copysign_one(d.z)) * 1e-20,
                        lessThan(abs(d), vec3(1e-20)));
  r.inv_d = 1.0 / safe;
  const vec3 a = abs(d);
  r.kz = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
  r.kx = (r.kz + 1) % 3;
  r.ky = (r.kx + 1) % 3;
  if (d[r.kz] < 0.0) {  // keeps the winding, so the edge functions' signs mean inside
    const int k = r.kx;
    r.kx = r.ky;
    r.ky = k;
  }
  r.shear = vec3(d[r.kx] / d[r.kz], d[r.ky] / d[r.kz], 1.0 / d[r.kz]);
  return r;
}

void intersect_triangle(RayPre r, uint i, inout Hit h) {
  const Tri tri = tris[i];
  precise const vec3 A = tri.v0 - r.o;
  precise const vec3 B = tri.v1 - r.o;
  precise const vec3 C = tri.v2 - r.o;
  precise const float ax = A[r.kx] - r.shear.x * A[r.kz], ay = A[r.ky] - r.shear.y * A[r.kz];
  precise const float bx = B[r.kx] - r.shear.x * B[r.kz], by = B[r.ky] - r.shear.y * B[r.kz];
  precise const float cx = C[r.kx] - r.shear.x * C[r.kz], cy = C[r.ky] - r.shear.y * C[r.kz];
  precise const float U = cx * by - cy * bx;
  precise const float V = ax * cy - ay * cx;
  precise const float W = bx * ay - by * ax;
  if ((U < 0.0 || V < 0.0 || W < 0.0) && (U > 0.0 || V > 0.0 || W > 0.0)) return;
  precise const float det = U + V + W;
  if (det == 0.0) return;
  precise const float T = U * (r.shear.z * A[r.kz]) + V * (r.shear.z * B[r.kz]) +
                          W * (r.shear.z * C[r.kz]);
  const float s = det < 0.0 ? -1.0 : 1.0;  // compare T/det against (0, t) without dividing
  if (T * s <= 0.0 || T * s >= h.t * (det * s)) return;
  const float inv = 1.0 / det;
  h.t = T * inv;
  h.u = V * inv;
  h.v = W * inv;
  h.tri = i;
}

bool hit_box(vec3 lo, vec3 hi, RayPre r, float t_max, out float t_near) {
  const vec3 t0 = (lo - r.o) * r.inv_d, t1 = (hi - r.o) * r.inv_d;
  const vec3 tn = min(t0, t1), tf = max(t0, t1);
  t_near = max(max(tn.x, tn.y), max(tn.z, 0.0));
  const float t_far = min(min(tf.x, tf.y), tf.z) * 1.00000036;  // 1 + 2 gamma(3)
  return t_near <= min(t_far, t_max);
}

void intersect_leaf(RayPre r, uint first, uint count, inout Hit h) {
  for (uint k = 0u; k < count; ++k) intersect_triangle(r, first + k, h);
}

// Closest hit below node `root` nearer than h.t; updates h. With LS_ANY_HIT defined before
// this file is included: stops at the first leaf that gives a hit nearer than h.t.
void traverse(RayPre r, uint root, inout Hit h) {
  uint stack[kStackSize];
  int sp = 0;
  uint node = root;
  for (;;) {
    const Node n = nodes[node];
    float near0 = 0.0, near1 = 0.0;
    bool go0 = n.child0 != kNone && hit_box(n.lo0, n.hi0, r, h.t, near0);
    bool go1 = n.child1 != kNone && hit_box(n.lo1, n.hi1, r, h.t, near1);
    if (go0 && n.count0 > 0u) {
      intersect_leaf(r, n.child0, n.count0, h);
      go0 = false;
    }
    if (go1 && n.count1 > 0u) {
      intersect_leaf(r, n.child1, n.count1, h);
      go1 = false;
    }
#ifdef LS_ANY_HIT
    if (h.tri != kNone) break;  // a shadow ray (visibility.comp) needs any hit, not the closest
#endif
    if (go0 && go1) {  // nearer child first, the other waits on the stack
      const bool first0 = near0 <= near1;
      node = first0 ? n.child0 : n.child1;
      stack[sp++] = first0 ? n.child1 : n.child0;
    } else if (go0) {
      node = n.child0;
    } else if (go1) {
      node = n.child1;
    } else {
      if (sp == 0) break;
      node = stack[--sp];
    }
  }
}

Hit no_hit() {
  Hit h;
  h.t = kNoHit;
  h.tri = kNone;
  h.u = h.v = 0.0;
  h.inst = kNone;
  return h;
}

// Closest hit in the static geometry (the BVH rooted at node 0).
Hit trace_closest(vec3 o, vec3 d) {
  Hit h = no_hit();
  traverse(prepare_ray(o, d), 0u, h);
  return h;
}

// Interpolated like the Embree backend: more accurate than o + t d far from the origin.
vec3 hit_point(Hit h) {
  const Tri tri = tris[h.tri];
  return tri.v0 + h.u * (tri.v1 - tri.v0) + h.v * (tri.v2 - tri.v0);
}

#endif
