// Movable meshes (instances.glsl), shared by trace.comp and visibility.comp: the switch, the
// record (C++ twin: gpu::Instance in NativeSolver/src/vulkan/gpu_layout.hpp) and its buffer.
#ifndef LIGHTSOLVER_INSTANCE_LAYOUT_GLSL
#define LIGHTSOLVER_INSTANCE_LAYOUT_GLSL

#include "trace_bindings.h"

layout(constant_id = LS_SPEC_HAS_INSTANCES) const bool HAS_INSTANCES = true;  // movable meshes

// A movable mesh: its own BVH (in prepared coordinates) placed by a rigid transform.
struct Instance {
  mat4 to_world;   // PreparedMesh::transform
  mat4 to_object;  // its inverse
  vec3 lo; uint root;  // world box of the placed mesh; root node of its BVH
  vec3 hi; uint pad;
};

layout(std430, set = 0, binding = LS_BINDING_INSTANCES) readonly buffer Instances {
  Instance instances[];
};

#endif
