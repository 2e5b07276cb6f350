// Python keywords and Scene properties from the run options table: one loop per front end
// instead of a hand-written argument per option and function.
#include "run_option_keywords.hpp"

#include <pybind11/stl.h>

#include <cstring>
#include <type_traits>

namespace py = pybind11;
using namespace lightsolver;

bool every_keyword(const RunOptionInfo& row) { return row.python_keyword != nullptr; }

bool per_run_keyword(const RunOptionInfo& row) { return every_keyword(row) && !row.per_backend; }

bool checkpointed_keyword(const RunOptionInfo& row) {
  return every_keyword(row) && row.cost_and_study;
}

namespace {

template <class T>
const char* type_name() {
  if constexpr (std::is_same_v<T, bool>) return "bool";
  if constexpr (std::is_unsigned_v<T>) return "uint";
  if constexpr (std::is_integral_v<T>) return "int";
  if constexpr (std::is_floating_point_v<T>) return "float";
  return "str";
}

// A Python value as the row's type, range-checked; `where` names it in errors.
template <class T>
T checked_value(const py::handle& value, const RunOptionInfo& info, const std::string& where) {
  if constexpr (std::is_arithmetic_v<T> && !std::is_same_v<T, bool>) {
    // The range first, as a number: photons=0 and photons=-1 get the CLI's message.
    if (py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value)) {
      check_range(info, value.cast<double>(), "", where);
    }
  }
  try {
    T v = value.cast<T>();
    if constexpr (std::is_same_v<T, std::string>) {
      if (!is_choice(info, v)) throw InputError("", where, choice_error(info, v));
    }
    return v;
  } catch (const py::cast_error&) {
    throw py::type_error(where + ": expected " + type_name<T>() + ", got " +
                         std::string(py::repr(value)));
  }
}

// The Python keyword's default: None for scene settings (the scene's value applies), the
// SolveOptions default for options of a run only.
template <class Row>
py::object keyword_default(const Row& row) {
  if constexpr (Row::kInScene) {
    return py::none();
  } else {
    return py::cast(row.default_value());
  }
}

bool listed(const char* name, std::initializer_list<const char*> names) {
  for (const char* n : names) {
    if (std::strcmp(n, name) == 0) return true;
  }
  return false;
}

}  // namespace

std::string python_command(const char* function) {
  const bool simulation = std::strcmp(function, "run") == 0 ||
                          std::strcmp(function, "refine") == 0 ||
                          std::strcmp(function, "combine") == 0;
  std::string text =
      std::string("python: lightsolver.") + (simulation ? "Simulation." : "") + function;
  // The script that called it, where Python knows one (FreeCAD's embedded interpreter may not).
  const py::module_ sys = py::module_::import("sys");
  if (!py::hasattr(sys, "argv")) return text;
  std::string argv;
  for (const py::handle a : sys.attr("argv")) {
    argv += (argv.empty() ? "" : " ") + std::string(py::str(a));
  }
  return argv.empty() ? text : text + " in " + argv;
}

void set_run_options(const py::kwargs& keywords, SolveOptions& options, const KeywordFilter& take,
                     std::initializer_list<const char*> own, const char* function) {
  options.command = python_command(function);
  for (const auto& [key, value] : keywords) {
    const std::string name = py::str(key);
    if (listed(name.c_str(), own)) continue;
    bool known = false;
    for_each_run_option([&](const auto& row) {
      using Row = std::decay_t<decltype(row)>;
      if constexpr (Row::kInRun) {
        if (known || !take(row.info) || name != row.info.python_keyword) return;
        known = true;
        using T = typename Row::value_type;
        if (value.is_none()) {
          options.*row.option = SolveOptions{}.*row.option;
        } else {
          options.*row.option = checked_value<T>(value, row.info, name);
        }
      }
    });
    if (!known) {
      throw py::type_error(std::string(function) + "() got an unexpected keyword argument '" +
                           name + "'");
    }
  }
}

std::string keywords_doc(const KeywordFilter& take) {
  std::string doc;
  for_each_run_option([&](const auto& row) {
    if constexpr (std::decay_t<decltype(row)>::kInRun) {
      if (!take(row.info)) return;
      const std::string range = range_text(row.info.range);
      const std::string note = row.info.scene_key ? default_note(row) : "";
      doc += std::string("\n  ") + row.info.python_keyword + "=" +
             std::string(py::repr(keyword_default(row))) + ": " + row.info.help +
             (range.empty() ? "" : " " + range) + (note.empty() ? "" : " (default: " + note + ")");
    }
  });
  return doc;
}

void bind_scene_settings(py::class_<Scene>& scene) {
  for_each_run_option([&](const auto& row) {
    using Row = std::decay_t<decltype(row)>;
    if constexpr (Row::kInScene) {
      using T = typename Row::value_type;
      const auto member = row.setting;
      const RunOptionInfo info = row.info;
      scene.def_property(
          row.info.scene_key, [member](const Scene& s) { return s.settings.*member; },
          [member, info](Scene& s, const py::object& value) {
            // None unsets an optional setting (max_seconds); others need a value.
            if constexpr (std::is_same_v<decltype(s.settings.*member), std::optional<T>&>) {
              if (value.is_none()) {
                s.settings.*member = std::nullopt;
                return;
              }
            }
            s.settings.*member = checked_value<T>(value, info, info.scene_key);
          },
          (std::string(row.info.help) + " (default: " + default_note(row) + ")").c_str());
    }
  });
}

py::list run_options_list() {
  py::list out;
  for_each_run_option([&](const auto& row) {
    using Row = std::decay_t<decltype(row)>;
    using T = typename Row::value_type;
    const RunOptionInfo& i = row.info;
    const auto text = [](const char* s) {
      return s ? py::object(py::str(s)) : py::object(py::none());
    };
    const bool ranged = !range_text(i.range).empty();
    py::dict d;
    d["name"] = i.name;
    d["type"] = type_name<T>();
    d["default"] = py::cast(row.default_value());
    d["help"] = i.help;
    d["min"] = ranged ? py::object(py::float_(i.range.min)) : py::object(py::none());
    d["max"] = ranged ? py::object(py::float_(i.range.max)) : py::object(py::none());
    d["min_open"] = i.range.min_open;
    d["max_open"] = i.range.max_open;
    d["range"] = range_text(i.range);
    d["scene_key"] = text(i.scene_key);
    d["cli_flag"] = text(i.cli_flag);
    d["python_keyword"] = text(i.python_keyword);
    d["python_default"] = i.python_keyword ? keyword_default(row) : py::none();
    d["result_key"] = text(i.result_key);
    d["echoed_when"] = text(i.echoed_when);
    d["cost_and_study"] = i.cost_and_study;
    d["per_backend"] = i.per_backend;
    out.append(d);
  });
  return out;
}
