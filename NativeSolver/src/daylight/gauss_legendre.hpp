#pragma once
// Gauss–Legendre rules on [0, 1], shared by the sky models' horizontal integral
// (sky_models.cpp) and the sky vectors' patch integrals (sky_vector.cpp).
#include <cmath>
#include <cstddef>
#include <numbers>
#include <vector>

namespace lightsolver::daylight {

/// Nodes `x` and weights `w` of an n-point rule on [0, 1] (the weights add up to 1).
struct GaussRule {
  std::vector<double> x, w;
};

/// The n-point Gauss–Legendre rule on [0, 1], n ≥ 1: nodes by Newton's method on P_n.
inline GaussRule gauss_legendre(int n) {
  GaussRule r;
  r.x.resize(static_cast<std::size_t>(n));
  r.w.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < (n + 1) / 2; ++i) {
    double z = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5)), dp = 1.0;
    for (int it = 0; it < 100; ++it) {
      double p1 = 1.0, p2 = 0.0;
      for (int j = 1; j <= n; ++j) {
        const double p3 = p2;
        p2 = p1;
        p1 = ((2.0 * j - 1.0) * z * p2 - (j - 1.0) * p3) / j;
      }
      dp = n * (z * p1 - p2) / (z * z - 1.0);
      const double step = p1 / dp;
      z -= step;
      if (std::abs(step) < 1e-15) break;
    }
    const auto a = static_cast<std::size_t>(i), b = static_cast<std::size_t>(n - 1 - i);
    r.x[a] = 0.5 * (1.0 - z);
    r.x[b] = 0.5 * (1.0 + z);
    r.w[a] = r.w[b] = 1.0 / ((1.0 - z * z) * dp * dp);
  }
  if (n == 1) r.x[0] = 0.5, r.w[0] = 1.0;
  return r;
}

}  // namespace lightsolver::daylight
