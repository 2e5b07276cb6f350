// The direct solver: prepare the scene, trace photons in batches (progress and cancellation
// between batches), then turn integer tallies into illuminance estimates.
#include "lightsolver/solver.hpp"

#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>

#include "core/backend.hpp"

namespace lightsolver {
namespace {

std::unique_ptr<detail::Backend> make_backend(const std::string& name,
                                              const detail::PreparedScene& scene) {
  if (name == "auto" || name == "embree") return detail::make_embree_backend(scene);
  throw InputError("", "backend", "unknown backend \"" + name + "\" (expected auto or embree)");
}

// Batches give progress reports and cancellation points; their size does not change results.
// In accuracy mode they double from 2^14 so a goal met early is seen early.
std::uint64_t next_batch(std::uint64_t done, std::uint64_t total, bool accuracy_mode) {
  const std::uint64_t size =
      accuracy_mode ? std::max<std::uint64_t>(done, 1u << 14)
                    : std::clamp<std::uint64_t>(total / 100, 1u << 14, 1u << 22);
  return std::min(size, total - done);
}

// True when every target's interval is narrow enough relative to its mean. A target with no
// hit yet cannot be judged: keep tracing.
bool accuracy_reached(const detail::PreparedScene& s, const detail::TallyBlock& t,
                      std::uint64_t photons, double confidence, double goal) {
  for (const std::uint32_t bin : s.target_bin) {
    const Estimate e = make_estimate(t.bins[bin], photons, 1.0, confidence);
    if (e.hits == 0 || 0.5 * (e.ci_high - e.ci_low) > goal * e.mean) return false;
  }
  return true;
}

TargetResult make_target(const Target& t, const detail::PreparedScene& s,
                         const detail::TallyBlock& tallies, std::uint32_t bin,
                         std::uint64_t photons, double confidence) {
  TargetResult r;
  r.name = t.name;
  r.is_grid = t.type == Target::Type::Grid;
  r.area_m2 = s.bins[bin].area_m2;
  auto estimate = [&](std::uint32_t b) {
    return make_estimate(tallies.bins[b], photons, s.total_flux_lm / s.bins[b].area_m2,
                         confidence);
  };
  r.estimate = estimate(bin);
  if (!r.is_grid) return r;
  r.nu = t.nu;
  r.nv = t.nv;
  r.cells.reserve(std::size_t(t.nu) * t.nv);
  for (std::uint32_t c = 0; c < t.nu * t.nv; ++c) r.cells.push_back(estimate(bin + 1 + c));
  const auto [lo, hi] = std::minmax_element(r.cells.begin(), r.cells.end(),
                                            [](auto& a, auto& b) { return a.mean < b.mean; });
  r.min_lux = lo->mean;
  r.max_lux = hi->mean;
  r.uniformity = r.estimate.mean > 0.0 ? r.min_lux / r.estimate.mean : 0.0;
  return r;
}

void add_warnings(const Scene& scene, Results& r) {
  r.warnings = scene.warnings;
  if (r.total_flux_lm <= 0.0) r.warnings.push_back("all luminaires have zero flux");
  if (r.capped_paths > 0) {
    r.warnings.push_back(std::to_string(r.capped_paths) +
                         " photon path(s) were still alive at max_bounces = " +
                         std::to_string(scene.settings.max_bounces) +
                         "; their remaining light is lost, so results are biased low");
  }
  if (r.partial) r.warnings.push_back("run stopped early: results are from the photons traced");
  if (r.target_accuracy && !r.accuracy_met && !r.partial) {
    r.warnings.push_back("the photon budget ran out before every target reached the requested "
                         "accuracy");
  }
}

}  // namespace

const char* version() { return LIGHTSOLVER_VERSION; }

Results solve(const Scene& scene, const SolveOptions& options, const ProgressFn& progress) {
  const auto start = std::chrono::steady_clock::now();
  Results r;
  r.photons_requested = options.photons.value_or(scene.settings.photons);
  r.seed = options.seed.value_or(scene.settings.seed);
  r.confidence = options.confidence.value_or(scene.settings.confidence);
  if (r.photons_requested == 0) throw InputError("", "photons", "must be at least 1");
  if (!(r.confidence > 0.0 && r.confidence < 1.0)) {
    throw InputError("", "confidence", "must lie strictly between 0 and 1");
  }
  if (options.threads < 0) throw InputError("", "threads", "must be >= 0 (0: all cores)");
  r.target_accuracy = options.target_accuracy;
  if (r.target_accuracy && !(*r.target_accuracy > 0.0 && *r.target_accuracy < 1.0)) {
    throw InputError("", "target_accuracy", "must lie strictly between 0 and 1 (e.g. 0.02)");
  }

  const detail::PreparedScene prepared = detail::prepare(scene);
  r.total_flux_lm = prepared.total_flux_lm;
  detail::TallyBlock tallies(prepared.bins.size());
  if (prepared.total_flux_lm > 0.0) {
    auto backend = make_backend(options.backend, prepared);
    r.backend = backend->name();
    tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
    const bool accuracy_mode = r.target_accuracy.has_value();
    while (r.photons < r.photons_requested) {
      if (options.cancel && options.cancel->load()) break;
      const std::uint64_t n = next_batch(r.photons, r.photons_requested, accuracy_mode);
      arena.execute([&] { backend->trace(r.photons, n, r.seed, tallies); });
      r.photons += n;
      if (accuracy_mode &&
          accuracy_reached(prepared, tallies, r.photons, r.confidence, *r.target_accuracy)) {
        r.accuracy_met = true;
        break;
      }
      if (progress && !progress(r.photons, r.photons_requested)) break;
    }
  } else {
    r.backend = options.backend == "auto" ? "embree" : options.backend;
    r.photons = r.photons_requested;  // nothing to trace: every estimate is exactly zero
  }
  r.partial = r.photons < r.photons_requested && !r.accuracy_met;
  r.ray_segments = tallies.ray_segments;
  r.capped_paths = tallies.capped_paths;
  for (std::size_t i = 0; i < scene.targets.size(); ++i) {
    r.targets.push_back(make_target(scene.targets[i], prepared, tallies, prepared.target_bin[i],
                                    r.photons, r.confidence));
  }
  add_warnings(scene, r);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace lightsolver
