// The common subset of GLSL 4.60 and C++20 that the physics headers in this folder are written
// in, so the Vulkan shaders and the CPU solver include one text of each formula (docs/solver.md,
// "Physics written once"). Both preprocessors read these files; only C++ defines __cplusplus.
//
// Rules of the subset (each keeps the two compiled results bit for bit the same):
// - glm mirrors GLSL: vec3, uvec4, dot, normalize, floatBitsToInt, umulExtended ... mean the same
//   on both sides. Scalar math (sqrt, cos, sin, abs, max, min) is std's overload in C++.
// - Float literals always carry `f` (GLSL 4.x accepts it; in C++ an unsuffixed literal is a double
//   and would change the result). A formula generic in its precision writes Real(0.5).
// - Parameters: plain values, LS_OUT(T) / LS_INOUT(T) for results (out/inout in GLSL, T& in C++).
//   LS_IN(T) (in T in GLSL, const T& in C++; the same value either way) for vectors a hot loop
//   reads from memory into a function with an early exit: GCC copies a by-value vec3 argument at
//   the call, loading every component before the first test even when inlined (grid_crossing).
// - Random numbers: LS_UNIFORM() is the next uniform float of the path's stream (PathRng in C++, a
//   private global stream in GLSL, Shaders/philox.glsl). A function that draws takes
//   LS_RNG_PARAM (after other parameters) or LS_RNG_ONLY (alone), and passes the stream on with
//   LS_RNG_ARG / LS_RNG_ONLY_ARG.
// - Every function is LS_FN (inline in C++). In C++ everything lives in lightsolver::shared.
#ifndef LIGHTSOLVER_SHARED_PRELUDE_H
#define LIGHTSOLVER_SHARED_PRELUDE_H

#ifdef __cplusplus

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/integer.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#define LS_FN inline
#define LS_IN(T) const T&
#define LS_OUT(T) T&
#define LS_INOUT(T) T&
#define LS_RNG_PARAM , PathRng& rng
#define LS_RNG_ONLY PathRng& rng
#define LS_RNG_ARG , rng
#define LS_RNG_ONLY_ARG rng
#define LS_UNIFORM() rng.uniform()

namespace lightsolver {
class PathRng;
namespace shared {
// GLSL's names for glm's types and functions, and std's float overloads of the scalar ones (the
// using-declarations hide the C library's double-only ::sqrt, ::cos ...).
using glm::bitfieldReverse;
using glm::dot;
using glm::floatBitsToInt;
using glm::floatBitsToUint;
using glm::intBitsToFloat;
using glm::normalize;
using glm::uint;
using glm::uintBitsToFloat;
using glm::umulExtended;
using glm::uvec2;
using glm::uvec4;
using glm::vec2;
using glm::vec3;
using std::abs;
using std::cos;
using std::max;
using std::min;
using std::sin;
using std::sqrt;
}  // namespace shared
}  // namespace lightsolver

#else  // GLSL

#define LS_FN
#define LS_IN(T) in T
#define LS_OUT(T) out T
#define LS_INOUT(T) inout T
#define LS_RNG_PARAM
#define LS_RNG_ONLY
#define LS_RNG_ARG
#define LS_RNG_ONLY_ARG
#define LS_UNIFORM() rng_uniform()

#endif

#endif
