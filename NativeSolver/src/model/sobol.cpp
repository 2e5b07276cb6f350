#include "model/sobol.hpp"

#include <boost/random/sobol.hpp>

#include "shared/philox.h"

namespace lightsolver::detail {

const SobolDirections& sobol_directions() {
  static const SobolDirections table = [] {
    // Boost's lattice of the Joe-Kuo table: element dims * j + d is dimension d's direction
    // number for index bit j, left-aligned in 32 bits (stored here reversed).
    const boost::random::qrng_detail::sobol_lattice<std::uint32_t, 32,
                                                    boost::random::default_sobol_table>
        lattice(kSobolDims);
    SobolDirections v{};
    for (unsigned j = 0; j < 32; ++j) {
      for (unsigned d = 0; d < kSobolDims; ++d)
        v[j][d] = reverse_bits(*lattice.iter_at(kSobolDims * j + d));
    }
    return v;
  }();
  return table;
}

SobolScramble::SobolScramble(std::uint64_t seed, std::uint32_t stream) {
  const glm::uvec2 key(static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32));
  for (unsigned q = 0; q < kSobolDims / 4; ++q) {
    const glm::uvec4 b = shared::philox4x32_10(glm::uvec4(q, 0u, 0xFFFFFFFFu, stream), key);
    seeds[4 * q] = b.x;
    seeds[4 * q + 1] = b.y;
    seeds[4 * q + 2] = b.z;
    seeds[4 * q + 3] = b.w;
  }
}

}  // namespace lightsolver::detail
