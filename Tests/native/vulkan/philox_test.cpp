// The GLSL stream (Shaders/philox.glsl around Shaders/shared/philox.h) must reproduce
// lightsolver::PathRng bit for bit, or the two backends would not trace the same photon paths for
// a seed. PathRng runs the same shared/philox.h compiled as C++; core rng_test.cpp holds it to
// Random123, so this compares the GPU with Random123 too.
#include <cmath>
#include <cstring>

#include "lightsolver/rng.hpp"
#include "vulkan/gpu_scene.hpp"
#include "vulkan_test_util.hpp"

namespace lightsolver::test {
namespace {

constexpr std::uint32_t kPhiloxSpirv[] = {
#include "philox_test.spv.inc"
};

struct PhiloxPush {
  std::uint64_t seed, first_path;
  std::uint32_t path_count, words_per_path;
};

using PhiloxTest = VulkanTest;

TEST_F(PhiloxTest, GlslMatchesRandom123BitForBit) {
  const vkw::Context ctx;
  constexpr std::uint32_t kPaths = 4096, kWords = 13;  // 13 words: crosses 3 counter blocks
  for (const std::uint64_t seed : {1ull, 0xDEADBEEFCAFEF00Dull}) {
    for (const std::uint64_t first : {0ull, (1ull << 32) - 100}) {  // path ids above 2^32 too
      vkw::Buffer out(ctx, kPaths * (kWords + 4) * 4, vkw::MemoryKind::Readback, "words");
      const PhiloxPush push{seed, first, kPaths, kWords};
      run_kernel(ctx, kPhiloxSpirv, {&out}, &push, sizeof(push), kPaths);
      const auto* gpu = static_cast<const std::uint32_t*>(out.mapped());
      int mismatches = 0;
      for (std::uint32_t i = 0; i < kPaths; ++i) {
        PathRng rng(seed, first + i);
        const std::uint32_t* w = gpu + i * (kWords + 4);
        for (std::uint32_t k = 0; k < kWords; ++k) mismatches += w[k] != rng.next_u32();
        const float u0 = rng.uniform(), u1 = rng.uniform();
        mismatches += std::memcmp(&w[kWords], &u0, 4) != 0;
        mismatches += std::memcmp(&w[kWords + 1], &u1, 4) != 0;
        // The 53-bit integer behind uniform_double(), rebuilt from the GPU's two words.
        const double d = rng.uniform_double();
        const std::uint64_t bits = (std::uint64_t(w[kWords + 3]) << 32) | w[kWords + 2];
        mismatches += static_cast<double>(bits) * 0x1p-53 != d;
      }
      EXPECT_EQ(mismatches, 0) << "seed " << seed << " first path " << first;
    }
  }
}

// The integer thresholds make the GPU's probability tests equal the CPU's double compares.
TEST(ProbabilityThreshold, EqualsTheCpuCompareForEveryUniform) {
  for (const double p : {0.0, 1e-9, 0.2, 0.5, 0.75, 1.0 / 3.0, 0.9999999, 1.0}) {
    const std::uint32_t t = detail::probability_threshold(p);
    for (std::uint32_t k : {0u, 1u, t > 0 ? t - 1 : 0u, t, t + 1, (1u << 24) - 1}) {
      if (k >= (1u << 24)) continue;
      const float u = static_cast<float>(k) * 0x1p-24f;
      EXPECT_EQ(u < p, k < t) << "p " << p << " k " << k;
    }
  }
  for (const double c : {0.0, 0.1, 1.0 / 3.0, 0.999999999, 1.0}) {
    const std::uint64_t t = detail::cdf_threshold(c);
    for (std::uint64_t j : {std::uint64_t(0), t > 0 ? t - 1 : 0, t, (std::uint64_t(1) << 53) - 1}) {
      EXPECT_EQ(static_cast<double>(j) * 0x1p-53 < c, j < t) << "c " << c << " j " << j;
    }
  }
}

}  // namespace
}  // namespace lightsolver::test
