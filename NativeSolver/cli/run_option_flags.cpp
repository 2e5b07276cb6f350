// Run option flags from the table: one loop instead of a hand-written add_option per option.
#include "run_option_flags.hpp"

#include <cstdlib>
#include <string>
#include <string_view>
#include <type_traits>

#include "backend_option.hpp"
#include "lightsolver/run_options.hpp"

namespace lightsolver::cli {
namespace {

// Refuses a value outside the row's range with the message the scene reader and Python give
// (CLI11 prefixes the flag). Text that is no number is left to CLI11's conversion error.
CLI::Validator range_check(const RunOptionInfo& info) {
  return CLI::Validator(
      [info](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0') return "";
        return range_error(info, v);
      },
      range_text(info.range));
}

template <class Row>
void add_flag(CLI::App* command, SolveOptions& options, const Row& row) {
  using T = typename Row::value_type;
  const RunOptionInfo& info = row.info;
  auto& member = options.*row.option;
  const std::string note = default_note(row);
  const std::string help = info.help + (note.empty() ? "" : " (default: " + note + ")");
  if constexpr (std::is_same_v<T, bool>) {
    command->add_flag_callback(
        info.cli_flag, [&member] { member = true; }, help);
  } else if constexpr (std::is_same_v<T, std::string>) {
    if (info.choices) {
      CLI::Option* flag = command->add_option(info.cli_flag, member, help);
      flag->check(CLI::Validator(
          [info](std::string& text) { return is_choice(info, text) ? "" : choice_error(info, text); },
          info.choices));
    } else if constexpr (std::is_same_v<std::decay_t<decltype(member)>, std::string>) {
      add_backend_option(command, member);  // its choices and help: the backend registry's
    }
  } else {
    CLI::Option* flag = command->add_option(info.cli_flag, member, help);
    if (!range_text(info.range).empty()) flag->check(range_check(info));
  }
}

}  // namespace

void add_run_option_flags(CLI::App* command, SolveOptions& options, bool checkpointed) {
  for_each_run_option([&](const auto& row) {
    if constexpr (std::decay_t<decltype(row)>::kInRun) {
      if (row.info.cli_flag && (!checkpointed || row.info.cost_and_study)) {
        add_flag(command, options, row);
      }
    }
  });
}

const char* flag_of(const char* name) {
  const RunOptionInfo* info = find_run_option(name);
  return info && info->cli_flag ? info->cli_flag : name;
}

}  // namespace lightsolver::cli
