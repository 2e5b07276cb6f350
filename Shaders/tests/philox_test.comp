#version 460
// Test kernel: the first words of PathRng(seed, path) for paths first + i, and the same path's
// uniform() and 53-bit draws, so the C++ test can compare them bit for bit with Random123.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

layout(local_size_x = 64) in;

#include "philox.glsl"

layout(std430, set = 0, binding = 0) writeonly buffer Words { uint words[]; };

layout(push_constant) uniform Push {
  uint64_t seed;
  uint64_t first_path;
  uint path_count;
  uint words_per_path;  // raw words, then 2 uniforms as float bits, then one 53-bit value
} pc;

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= pc.path_count) return;
  rng_init(pc.seed, pc.first_path + uint64_t(i), 0u);
  const uint base = i * (pc.words_per_path + 4u);
  for (uint k = 0u; k < pc.words_per_path; ++k) words[base + k] = rng_u32();
  words[base + pc.words_per_path] = floatBitsToUint(rng_uniform());
  words[base + pc.words_per_path + 1u] = floatBitsToUint(rng_uniform());
  const uvec2 d = unpackUint2x32(rng_u53());
  words[base + pc.words_per_path + 2u] = d.x;
  words[base + pc.words_per_path + 3u] = d.y;
}
