// The run options table's checks: one message per out-of-range value, which every front end
// gives under its own name for the field (settings.confidence, --confidence, confidence).
#include "lightsolver/run_options.hpp"

#include <cstdio>

namespace lightsolver {
namespace {

std::string number_text(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.15g", v);
  return buf;
}

// What the range asks for, from the side `value` breaks ("must be at least 1").
std::string requirement(const OptionRange& r, double value) {
  const bool has_min = std::isfinite(r.min), has_max = std::isfinite(r.max);
  if (has_min && has_max && r.min_open && r.max_open) {
    return "must lie strictly between " + number_text(r.min) + " and " + number_text(r.max);
  }
  if (!std::isfinite(value)) return "must be a finite number";
  if (has_min && (r.min_open ? !(value > r.min) : !(value >= r.min))) {
    return (r.min_open ? "must be > " : "must be at least ") + number_text(r.min);
  }
  return (r.max_open ? "must be < " : "must be <= ") + number_text(r.max);
}

template <class T>
std::optional<double> numeric(const T& v) {
  if constexpr (std::is_arithmetic_v<T> && !std::is_same_v<T, bool>) {
    return static_cast<double>(v);
  } else {
    return std::nullopt;
  }
}

template <class T>
std::optional<double> numeric(const std::optional<T>& v) {
  return v ? numeric(*v) : std::nullopt;
}

// A text option's value outside its choices: the message, else "".
template <class T>
std::string text_error(const RunOptionInfo& info, const T& v) {
  if constexpr (std::is_same_v<T, std::string>) {
    return is_choice(info, v) ? "" : choice_error(info, v);
  } else if constexpr (std::is_same_v<T, std::optional<std::string>>) {
    return v ? text_error(info, *v) : "";
  } else {
    return "";
  }
}

}  // namespace

bool is_choice(const RunOptionInfo& option, std::string_view value) {
  if (!option.choices) return true;
  std::string_view rest = option.choices;
  for (;;) {
    const auto bar = rest.find('|');
    if (rest.substr(0, bar) == value) return true;
    if (bar == std::string_view::npos) return false;
    rest.remove_prefix(bar + 1);
  }
}

std::string choice_error(const RunOptionInfo& option, std::string_view value) {
  std::string list = option.choices ? option.choices : "";
  for (char& c : list) {
    if (c == '|') c = ',';
  }
  std::string out;
  for (char c : list) {
    out += c;
    if (c == ',') out += ' ';
  }
  return "must be one of " + out + " (got \"" + std::string(value) + "\")";
}

std::vector<RunOptionInfo> run_option_infos() {
  std::vector<RunOptionInfo> out;
  for_each_run_option([&](const auto& row) { out.push_back(row.info); });
  return out;
}

const RunOptionInfo* find_run_option(std::string_view name) {
  static const std::vector<RunOptionInfo> infos = run_option_infos();
  for (const RunOptionInfo& o : infos) {
    if (name == o.name) return &o;
  }
  return nullptr;
}

std::string value_text(double value) { return number_text(value); }

std::string range_text(const OptionRange& r) {
  if (!std::isfinite(r.min) && !std::isfinite(r.max)) return "";
  const bool open_min = r.min_open || !std::isfinite(r.min);
  const bool open_max = r.max_open || !std::isfinite(r.max);
  return (open_min ? "(" : "[") + number_text(r.min) + ", " + number_text(r.max) +
         (open_max ? ")" : "]");
}

std::string range_error(const RunOptionInfo& option, double value) {
  const OptionRange& r = option.range;
  const bool inside = std::isfinite(value) && (r.min_open ? value > r.min : value >= r.min) &&
                      (r.max_open ? value < r.max : value <= r.max);
  if (inside) return "";
  return requirement(r, value) + " (got " + number_text(value) + ")";
}

void check_range(const RunOptionInfo& option, double value, const std::string& file,
                 const std::string& where) {
  const std::string error = range_error(option, value);
  if (!error.empty()) throw InputError(file, where, error);
}

void check_run_options(const SolveOptions& options) {
  for_each_run_option([&](const auto& row) {
    if constexpr (std::decay_t<decltype(row)>::kInRun) {
      if (const auto v = numeric(options.*row.option)) check_range(row.info, *v, "", row.info.name);
      const std::string error = text_error(row.info, options.*row.option);
      if (!error.empty()) throw InputError("", row.info.name, error);
    }
  });
}

std::vector<std::pair<std::string, std::string>> settings_errors(const Settings& settings) {
  std::vector<std::pair<std::string, std::string>> out;
  for_each_run_option([&](const auto& row) {
    if constexpr (std::decay_t<decltype(row)>::kInScene) {
      if (const auto v = numeric(settings.*row.setting)) {
        std::string error = range_error(row.info, *v);
        if (!error.empty())
          out.emplace_back(std::string("settings.") + row.info.scene_key, std::move(error));
      }
      std::string error = text_error(row.info, settings.*row.setting);
      if (!error.empty()) {
        out.emplace_back(std::string("settings.") + row.info.scene_key, std::move(error));
      }
    }
  });
  return out;
}

}  // namespace lightsolver
