#pragma once
// One fuzz input for each parser, shared by the libFuzzer targets and the replay test that
// always runs under ctest. Parsing may succeed or throw InputError; anything else (another
// exception, a crash, a non-finite sample) is a bug.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "lightsolver/photometry.hpp"

namespace lightsolver::fuzz {

/// Aborts (what a fuzzer reports) when a value a caller relies on is not finite.
inline void require(bool ok) {
  if (!ok) std::abort();
}

/// Drives what the solver does with a parsed file: sampler, lookups, and (for some inputs,
/// it is slow-ish) the summary.
inline void exercise(const PhotometricData& data, std::size_t size) {
  try {
    const PhotometricSampler sampler(data);
    require(std::isfinite(sampler.integrated_flux_lm()));
    for (std::uint64_t k = 0; k < 8; ++k) {
      PathRng rng(7, k);
      const glm::dvec3 d = sampler.sample_direction(rng);
      const glm::dvec3 o = sampler.sample_origin(rng);
      require(std::abs(d.x * d.x + d.y * d.y + d.z * d.z - 1.0) < 1e-9);
      require(std::isfinite(o.x) && std::isfinite(o.y) && o.z == 0.0);
      require(std::isfinite(sampler.intensity_cd(d)) && sampler.intensity_cd(d) >= 0.0);
    }
  } catch (const InputError&) {
    // A dark distribution: nothing to sample, nothing wrong.
  }
  if (size % 8 == 0) (void)photometry_summary(data);
}

/// True when parsed, false when rejected with InputError.
inline bool one_ies_input(const std::uint8_t* bytes, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(bytes), size);
  try {
    exercise(parse_ies(text, "fuzz.ies"), size);  // no directory: TILT=<file> is refused
    return true;
  } catch (const InputError&) {
    return false;
  }
}

/// True when parsed, false when rejected with InputError.
inline bool one_ldt_input(const std::uint8_t* bytes, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(bytes), size);
  try {
    exercise(parse_ldt(text, "fuzz.ldt"), size);
    return true;
  } catch (const InputError&) {
    return false;
  }
}

}  // namespace lightsolver::fuzz
