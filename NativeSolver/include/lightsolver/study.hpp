#pragma once
/// \file study.hpp
/// What accuracy costs, shown (`lightsolver study`, Python `lightsolver.study`): ONE run with
/// checkpoints at doubling photon counts (photon i is photon i, nothing is traced twice); at
/// each, the wall time, the per-cell interval widths (lightsolver/accuracy.hpp), Em, Emin and
/// U0, and against a reference (a long run's results file, or a closed form written as one)
/// the actual error; then the photons and seconds per-cell accuracy goals need, from an
/// N^-1/2 fit. docs/accuracy.md shows it for the examples.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "lightsolver/solver.hpp"

namespace lightsolver {

/// The checkpoints of a study: 10^4 photons, then 2x each, up to `max_photons` (empty below
/// 10^4).
std::vector<std::uint64_t> study_checkpoints(std::uint64_t max_photons);

/// A reference for a study: a results file (lightsolver.results/1) of the same scene.
struct StudyReference {
  std::string file;
  std::uint64_t photons = 0;
  std::vector<TargetResult> targets;  ///< means, intervals and cells as the file has them
};

/// Reads a reference results file for `scene`. Throws InputError naming the file when it is
/// missing, not a results file, or from another scene (other targets, cells or total flux).
StudyReference load_study_reference(const std::string& file, const Scene& scene);

/// One target's numbers at a checkpoint, or all targets' (`target` "*"). Values that do not
/// apply (Emin of a surface, errors without a reference) or cannot be judged yet are nullopt.
struct StudyStats {
  std::string target;
  std::optional<double> em_lux, em_ci_low_lux, em_ci_high_lux;  ///< the target's mean
  std::optional<double> emin_lux, emax_lux, u0;                 ///< grids: over cell means
  /// Per-cell relative half-widths (the rule of `--accuracy X --per-cell`): mean and worst.
  std::optional<double> mean_relative_half_width, worst_relative_half_width;
  /// |E - reference| / reference over the cells (the same rule for dark cells): mean and max.
  std::optional<double> mean_relative_error, max_relative_error;
  std::optional<double> em_relative_error;  ///< the target mean's
};

struct StudyRow {
  std::uint64_t photons = 0;
  double seconds = 0.0;           ///< tracing time so far (one run)
  std::vector<StudyStats> stats;  ///< [0]: all targets ("*"), then one per target
};

/// Photons and seconds a per-cell accuracy goal needs (worst cell), from the fit.
struct StudyGoal {
  double accuracy = 0.0;
  std::optional<double> photons, seconds;  ///< nullopt when no row could be fitted
  bool extrapolated = false;  ///< beyond the last checkpoint: an extrapolation of the fit
};

/// The N^-1/2 fit of the worst per-cell width, and measured exponents for comparison.
struct StudyFit {
  std::size_t rows = 0;  ///< rows fitted (the last ones with every cell judged, at most 4)
  std::optional<double> coefficient;  ///< worst width = coefficient / sqrt(photons)
  /// Least-squares slopes of log(quantity) against log(photons) over the rows that have it:
  /// -0.5 is the Monte Carlo rate.
  std::optional<double> mean_width_exponent, worst_width_exponent, mean_error_exponent,
      max_error_exponent;
};

struct Study {
  std::string scene_file;
  std::vector<StudyRow> rows;
  StudyFit fit;
  std::vector<StudyGoal> goals;  ///< kCostGoals
  std::optional<StudyReference> reference;
  std::optional<double> reference_mean_relative_half_width;  ///< the reference's own noise
  double prepare_seconds = 0.0;  ///< building the scene once, before tracing
  Results results;               ///< the run (its photons are the last row's)
  Warnings warnings;             ///< the study's own remarks (the run's are in results)
};

struct StudyOptions {
  SolveOptions solve;  ///< seed, confidence, threads, backend, cancel; photons are set here
  std::uint64_t max_photons = 10'240'000;
  std::string reference_file;  ///< empty: no reference, no errors
};

/// Runs a study. `on_row` is called as each checkpoint is reached (e.g. to print it). Throws
/// InputError for bad options or reference.
Study run_study(const Scene& scene, const StudyOptions& options,
                const std::function<void(const StudyRow&)>& on_row = {});

/// The study as JSON (`lightsolver.study/1`, docs/accuracy.md); no inf or NaN (null instead).
std::string study_to_json(const Study& study);

/// The study as CSV: one line per checkpoint and target ("*": all targets), empty fields where
/// a value does not apply.
std::string study_to_csv(const Study& study);

}  // namespace lightsolver
