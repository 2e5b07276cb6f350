// The one table of trace.comp's interface numbers: descriptor bindings (set 0) and
// specialisation constant ids (the luminaire types' follow from shared/luminaires.h). Both sides
// include this file: the GLSL (scene_layout.glsl, trace_layout.glsl, trace.comp) and the C++
// host (NativeSolver/src/vulkan/gpu_layout.hpp, whose kBuffers / kSpecConstants tables add the
// GLSL names). Plain #defines only: the one syntax the
// C++ and GLSL preprocessors share. Tests/native/vulkan/bindings_test.cpp reflects the compiled
// SPIR-V and fails when a number or name disagrees with the C++ tables.
#ifndef LIGHTSOLVER_TRACE_BINDINGS_H
#define LIGHTSOLVER_TRACE_BINDINGS_H

// Storage buffers (GLSL block name: contents).
#define LS_BINDING_NODES 0           // Nodes: BVH nodes
#define LS_BINDING_TRIS 1            // Tris: triangles in leaf order
#define LS_BINDING_TRI_NORMALS 2     // TriNormals: one normal per triangle
#define LS_BINDING_MESHES 3          // Meshes: material and surface bin per mesh
#define LS_BINDING_MATERIALS 4       // Materials
#define LS_BINDING_LUMINAIRES 5      // Luminaires
#define LS_BINDING_LUMINAIRE_CDF 6   // LuminaireCdf: 53-bit thresholds of the luminaire choice
#define LS_BINDING_GRIDS 7           // Grids
#define LS_BINDING_TALLIES 8         // Tallies: S, Q per bin
#define LS_BINDING_COUNTERS 9        // Counters: segments, capped, cut and retried paths
#define LS_BINDING_PHOTOMETRICS 10   // Photometrics: one record per photometric luminaire
#define LS_BINDING_PHOTO_FLOATS 11   // PhotoFloats: their sampler tables
#define LS_BINDING_PHOTO_CDF 12      // PhotoCdf: 53-bit thresholds of their cell choice
#define LS_BINDING_INSTANCES 13      // Instances: movable meshes
#define LS_BINDING_RETRY 14          // Retry: paths to trace again (lavapipe's loop limit)
#define LS_BINDING_SOBOL 15          // SobolDirections: Sobol' direction numbers (sobol.glsl)
#define LS_BINDING_COUNT 16
// visibility.comp's own, after trace.comp's (it reads the geometry at the bindings above).
#define LS_BINDING_SHADOW_RAYS 16    // ShadowRays: the chunk's shadow rays
#define LS_BINDING_VISIBLE 17        // Visible: one word per ray
#define LS_BINDING_VIS_RETRY 18      // VisRetry: rays to trace again (lavapipe's loop limit)
#define LS_VISIBILITY_BINDING_COUNT 19
// path_vertices.comp's own, after trace.comp's (it reads the scene and luminaires above).
#define LS_BINDING_PATH_VERTICES 16  // PathVertices: the diffuse vertices of a chunk's paths
#define LS_BINDING_PATH_CONTROL 17   // PathControl: retry dispatch, counts, paths to trace again
#define LS_PATH_BINDING_COUNT 18

// Specialisation constants (GLSL name). Ids 1.. switch features off for scenes without them.
#define LS_SPEC_WORKGROUP_SIZE 0    // local_size_x
#define LS_SPEC_HAS_DIFFUSE 1       // HAS_DIFFUSE
#define LS_SPEC_HAS_MIRROR 2        // HAS_MIRROR
#define LS_SPEC_HAS_GLASS 3         // HAS_GLASS
#define LS_SPEC_HAS_GLOSSY 4        // HAS_GLOSSY
#define LS_SPEC_HAS_GRIDS 5         // HAS_GRIDS
#define LS_SPEC_HAS_SURFACE_BINS 6  // HAS_SURFACE_BINS
#define LS_SPEC_MANY_LUMINAIRES 7   // MANY_LUMINAIRES
#define LS_SPEC_HAS_INSTANCES 8     // HAS_INSTANCES: movable meshes
#define LS_SPEC_QUASI_RANDOM 9      // QUASI_RANDOM: each path's Sobol' point first (sobol.glsl)
// Then one per luminaire type, the last ids: LS_SPEC_FIRST_LUMINAIRE + the type's code, named
// by its entry in LS_LUMINAIRE_TYPES (shared/luminaires.h), which lists the codes.
#define LS_SPEC_FIRST_LUMINAIRE 10

// Type codes in the packed materials (Material::Type values; the C++ side asserts they agree,
// vulkan/gpu_scene.cpp). The luminaires' are in shared/luminaires.h.
#define LS_MATERIAL_DIFFUSE 0
#define LS_MATERIAL_MIRROR 1
#define LS_MATERIAL_GLASS 2
#define LS_MATERIAL_GLOSSY 3

#endif
