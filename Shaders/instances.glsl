// Two-level tracing for movable meshes, as Embree instances do it: the static BVH first, then
// each instance whose world box the ray reaches, with the ray taken into the instance's
// prepared coordinates (rigid transform: t is the same in both spaces). The top level is a
// linear list: scenes move a handful of meshes, and the box test culls the others.
#ifndef LIGHTSOLVER_INSTANCES_GLSL
#define LIGHTSOLVER_INSTANCES_GLSL

// Closest hit nearer than t_max (LS_ANY_HIT, bvh.glsl: some hit nearer than t_max, if any).
Hit trace_scene_within(vec3 o, vec3 d, float t_max) {
  Hit h = no_hit();
  h.t = t_max;
  const RayPre world = prepare_ray(o, d);
  traverse(world, 0u, h);
  if (!HAS_INSTANCES) return h;
  for (uint k = 0u; k < pc.instance_count; ++k) {
#ifdef LS_ANY_HIT
    if (h.tri != kNone) break;
#endif
    float t_near;
    if (!hit_box(instances[k].lo, instances[k].hi, world, h.t, t_near)) continue;
    const mat4 m = instances[k].to_object;
    const uint before = h.tri;
    traverse(prepare_ray((m * vec4(o, 1.0)).xyz, mat3(m) * d), instances[k].root, h);
    if (h.tri != before) h.inst = k;  // leaf-order triangle indices are unique across BVHs
  }
  return h;
}

Hit trace_scene(vec3 o, vec3 d) { return trace_scene_within(o, d, kNoHit); }

// Front normal and hit point in world space (embree_backend.cpp: mat3(transform) * n, rigid).
vec3 hit_normal(Hit h) {
  const vec3 n = tri_normals[h.tri].xyz;
  if (!HAS_INSTANCES || h.inst == kNone) return n;
  return normalize(mat3(instances[h.inst].to_world) * n);
}

vec3 world_hit_point(Hit h) {
  const vec3 p = hit_point(h);
  if (!HAS_INSTANCES || h.inst == kNone) return p;
  return (instances[h.inst].to_world * vec4(p, 1.0)).xyz;
}

#endif
