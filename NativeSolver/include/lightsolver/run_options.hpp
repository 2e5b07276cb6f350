#pragma once
/// \file run_options.hpp
/// The run options, described once: one row per option with its name, help text, accepted
/// range and how each front end spells it (scene file `settings`, `lightsolver run` flag,
/// Python keyword, results key). The scene reader, validate(), the CLI's flags, the Python
/// module's keywords and Scene properties, and the results writer take their names, ranges and
/// help from here; the defaults are the in-class initializers of Settings (scene settings) and
/// SolveOptions (options of a run only), read back through the row's member pointers. Python
/// sees the table as `lightsolver.run_options()`.

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "lightsolver/scene.hpp"
#include "lightsolver/solver.hpp"

namespace lightsolver {

/// The values a numeric option accepts: finite, from `min` to `max`, either end open or closed.
struct OptionRange {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_open = false, max_open = false;
};

/// What an option is and how it is spelled; nullptr where a front end does not have it.
struct RunOptionInfo {
  const char* name;            ///< SolveOptions / Settings member; the name errors give
  const char* help;            ///< one line for `--help`, docstrings and the docs
  const char* scene_key;       ///< key of a scene file's `settings`
  const char* cli_flag;        ///< flag of `lightsolver run`
  const char* python_keyword;  ///< keyword of `lightsolver.solve()`
  const char* result_key;      ///< top-level key of the results JSON that echoes it
  const char* echoed_when;     ///< when the results carry `result_key` ("" always)
  OptionRange range;           ///< numeric options; the whole line for others
  bool cost_and_study;         ///< also an option of `cost` and `study` (checkpointed runs)
  bool per_backend;  ///< chosen when the backend is built (Simulation(), not Simulation.run())
  /// A text option's accepted values, "|"-separated ("auto|on|off"); nullptr: any (the
  /// backend's come from the registry).
  const char* choices = nullptr;
};

/// A row with no member on one side (a run-only option has no Settings member, a scene-only
/// setting no SolveOptions member).
struct NoMember {};
inline constexpr NoMember Settings::*kNoSetting = nullptr;
inline constexpr NoMember SolveOptions::*kNoOption = nullptr;

namespace detail {
template <class T>
struct Unwrapped {
  using type = T;
};
template <class T>
struct Unwrapped<std::optional<T>> {
  using type = T;
};
}  // namespace detail

/// One typed row: the description and the Settings and SolveOptions members it sets.
template <class S, class O>
struct RunOption {
  RunOptionInfo info;
  S Settings::*setting;
  O SolveOptions::*option;

  static constexpr bool kInScene = !std::is_same_v<S, NoMember>;
  static constexpr bool kInRun = !std::is_same_v<O, NoMember>;
  /// The value's type (bool, std::uint32_t, std::uint64_t, int, double or std::string).
  using value_type = typename detail::Unwrapped<std::conditional_t<kInRun, O, S>>::type;

  /// The default: the scene setting's (Settings{}) or, for run-only options, SolveOptions{}'s;
  /// empty for options that are unset by default (max_seconds, target_accuracy).
  std::optional<value_type> default_value() const {
    if constexpr (kInScene) {
      return Settings{}.*setting;
    } else {
      return SolveOptions{}.*option;
    }
  }
};

/// Every run option, in the order front ends list them. Add a row here (and its member to
/// Settings and/or SolveOptions); every front end, the docs test and the echo test follow.
// clang-format off
// Row: {name, help, scene key, CLI flag, Python keyword, results key, echoed when, range,
//       cost_and_study, per_backend}, Settings member, SolveOptions member.
inline constexpr std::tuple kRunOptions{
    // The most photons depend on max_bounces too: check_photon_count() checks them.
    RunOption{{"photons",
               "Photon paths to trace, at most 1e13 (fewer above 1357 bounces); for accuracy "
               "and decide runs: the budget",
               "photons", "--photons", "photons", "photons_requested", "", {1.0}, false, false},
              &Settings::photons, &SolveOptions::photons},
    RunOption{{"seed", "Random seed: the same scene, seed and photons give the same results",
               "seed", "--seed", "seed", "seed", "", {}, true, false},
              &Settings::seed, &SolveOptions::seed},
    RunOption{{"confidence", "Two-sided confidence level of the intervals, e.g. 0.95",
               "confidence", "--confidence", "confidence", "confidence", "",
               {0.0, 1.0, true, true}, true, false},
              &Settings::confidence, &SolveOptions::confidence},
    RunOption{{"threads", "Worker threads (0: all cores)",
               nullptr, "--threads", "threads", nullptr, nullptr, {0.0, 65536.0}, true, true},
              kNoSetting, &SolveOptions::threads},
    RunOption{{"backend", "Tracing backend (`lightsolver backends` lists them)",
               nullptr, "--backend", "backend", "backend", "always, as the backend that traced",
               {}, true, true},
              kNoSetting, &SolveOptions::backend},
    RunOption{{"target_accuracy",
               "Stop when every target's CI half-width is at most this fraction of its mean "
               "(e.g. 0.02); without a photon count the budget is 1e10 photons within the "
               "time limit",
               nullptr, "--accuracy", "target_accuracy", "target_accuracy", "when set",
               {0.0, 1.0, true, true}, false, false},
              kNoSetting, &SolveOptions::target_accuracy},
    RunOption{{"accuracy_per_cell",
               "Judge the accuracy goal per grid cell and surface target; cells darker than "
               "1% of their grid's mean are judged against that 1%",
               "accuracy_per_cell", "--per-cell", "accuracy_per_cell", "accuracy_per_cell",
               "with target_accuracy", {}, false, false},
              &Settings::accuracy_per_cell, &SolveOptions::accuracy_per_cell},
    RunOption{{"max_seconds",
               "Time limit of the tracing in seconds (without one, accuracy and decide runs "
               "without a photon count stop after 300 s); the scene's applies to runs without "
               "an explicit photon count",
               "max_seconds", "--max-seconds", "max_seconds", "max_seconds",
               "when a time limit applied", {0.0, std::numeric_limits<double>::infinity(), true, true}, false, false},
              &Settings::max_seconds, &SolveOptions::max_seconds},
    RunOption{{"decide",
               "Trace until every requirement's verdict is pass or fail, within the photon "
               "budget (else 1e10 photons) and the time limit (default 300 s)",
               "decide", "--decide", "decide", "decide", "when a target has requirements",
               {}, false, false},
              &Settings::decide, &SolveOptions::decide},
    RunOption{{"contributions",
               "Report each luminaire group's contribution per target and cell (what "
               "`lightsolver rescale` needs)",
               "contributions", "--contributions", "contributions", nullptr, nullptr, {},
               false, false},
              &Settings::contributions, &SolveOptions::contributions},
    RunOption{{"next_event",
               "Direct light at grids and surface targets by shadow rays (auto: for every "
               "luminaire type that has them, where the backend traces them; on; off: all "
               "by photons)",
               "next_event", "--next-event", "next_event", nullptr, nullptr, {}, true, false,
               "auto|on|off"},
              &Settings::next_event, &SolveOptions::next_event},
    RunOption{{"connect_reflections",
               "Reflected light at grids by shadow rays from the diffuse reflections of an "
               "independent photon stream to every cell, beyond a cell size (auto, the "
               "default: where every surface is diffuse, with next-event estimation, on the "
               "Embree backend, and the connected light is at least 2 % of the direct; on; "
               "off: by photons)",
               "connect_reflections", "--connect-reflections", "connect_reflections", nullptr,
               nullptr, {}, true, false, "auto|on|off"},
              &Settings::connect_reflections, &SolveOptions::connect_reflections},
    RunOption{{"max_bounces",
               "Safety limit on surface interactions per path (paths it stops bias the "
               "result low and are warned of)",
               "max_bounces", nullptr, nullptr, nullptr, nullptr,
               {0.0, double(limits::kMaxBounces)}, false, false},
              &Settings::max_bounces, kNoOption},
    // Quasi-random photons (issue 28; run/replicate_run.hpp). Kept together at the end.
    RunOption{{"sampler",
               "Photon sampler: random (independent photons) or sobol (Owen-scrambled Sobol' "
               "points for emission and the first bounces, intervals from independent "
               "replicates; Embree backend, a fixed photon count)",
               nullptr, "--sampler", "sampler", nullptr, nullptr, {}, false, false,
               "random|sobol"},
              kNoSetting, &SolveOptions::sampler},
    RunOption{{"replicates",
               "Independent randomisations of a sobol run, each with photons / replicates "
               "photons; intervals are Student-t with replicates - 1 degrees of freedom",
               nullptr, "--replicates", "replicates", nullptr, nullptr, {2.0, 1024.0}, false,
               false},
              kNoSetting, &SolveOptions::replicates},
};
// clang-format on

/// Calls `f(row)` for every row of kRunOptions, in order.
template <class F>
constexpr void for_each_run_option(F&& f) {
  std::apply([&](const auto&... row) { (f(row), ...); }, kRunOptions);
}

/// Every row's description, in table order.
std::vector<RunOptionInfo> run_option_infos();

/// The row named `name` (RunOptionInfo::name); nullptr when there is none.
const RunOptionInfo* find_run_option(std::string_view name);

/// The results key of option `name`: the table's, checked at compile time.
consteval const char* result_key(std::string_view name) {
  const char* key = nullptr;
  for_each_run_option([&](const auto& row) {
    if (name == row.info.name) key = row.info.result_key;
  });
  if (!key) throw "no results key for this option";  // not a constant expression: no build
  return key;
}

/// Why `value` is outside the option's range ("must lie strictly between 0 and 1 (got 2)"),
/// or "" when it is inside. The same text in every front end; each names the field its way.
std::string range_error(const RunOptionInfo& option, double value);

/// The range as an interval: "(0, 1)", "[0, 1000000]", "[1, inf)"; "" when any value goes.
std::string range_text(const OptionRange& range);

/// Throws InputError(file, where, range_error(...)) when `value` is out of `option`'s range.
void check_range(const RunOptionInfo& option, double value, const std::string& file,
                 const std::string& where);

/// A value as the docs and help show it: 1000000, 0.95, true, auto.
std::string value_text(double value);
inline std::string value_text(bool value) { return value ? "true" : "false"; }
inline std::string value_text(const std::string& value) { return value; }

/// Where a front end's option takes its default from, for help texts: "settings.photons =
/// 1000000" for a scene setting ("settings.max_seconds = none" when unset), the value for an
/// option of a run only ("" when unset).
template <class Row>
std::string default_note(const Row& row) {
  const auto value = row.default_value();
  std::string text;
  if (value) {
    if constexpr (std::is_arithmetic_v<typename Row::value_type> &&
                  !std::is_same_v<typename Row::value_type, bool>) {
      text = value_text(static_cast<double>(*value));
    } else {
      text = value_text(*value);
    }
  }
  if constexpr (Row::kInScene) {
    return std::string("settings.") + row.info.scene_key + " = " + (value ? text : "none");
  } else {
    return text;
  }
}

/// Whether `value` is one of `option`'s choices (true for an option without choices).
bool is_choice(const RunOptionInfo& option, std::string_view value);
/// "must be one of auto, on, off (got \"x\")".
std::string choice_error(const RunOptionInfo& option, std::string_view value);

/// Checks every option set in `options` against its row (InputError naming the option).
void check_run_options(const SolveOptions& options);

/// Every scene setting out of its row's range: (`settings.<key>`, range_error()), in table
/// order (validate() reports them).
std::vector<std::pair<std::string, std::string>> settings_errors(const Settings& settings);

}  // namespace lightsolver
