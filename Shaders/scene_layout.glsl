// GPU scene layout shared by every shader. Must match NativeSolver/src/vulkan/gpu_layout.hpp
// (std430; every struct is a multiple of 16 bytes so C++ and GLSL agree without padding rules).
// Binding numbers come from trace_bindings.h, which the C++ side includes too.
#ifndef LIGHTSOLVER_SCENE_LAYOUT_GLSL
#define LIGHTSOLVER_SCENE_LAYOUT_GLSL

#include "trace_bindings.h"

const uint kNone = 0xFFFFFFFFu;

// Binary BVH node holding both children's boxes (one fetch decides both). count == 0: child is
// a node index; count > 0: child is the first of `count` triangles; child == kNone: empty slot.
struct Node {
  vec3 lo0; uint child0;
  vec3 hi0; uint count0;
  vec3 lo1; uint child1;
  vec3 hi1; uint count1;
};

// Triangles in BVH leaf order, with the mesh and the primitive index they came from.
struct Tri {
  vec3 v0; uint mesh;
  vec3 v1; uint prim;
  vec3 v2; uint pad;
};

layout(std430, set = 0, binding = LS_BINDING_NODES) readonly buffer Nodes { Node nodes[]; };
layout(std430, set = 0, binding = LS_BINDING_TRIS) readonly buffer Tris { Tri tris[]; };
layout(std430, set = 0, binding = LS_BINDING_TRI_NORMALS) readonly buffer TriNormals {
  vec4 tri_normals[];
};

#endif
