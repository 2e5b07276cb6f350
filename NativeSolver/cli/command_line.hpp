#pragma once
// The command line this process was started with, as a shell would take it back: the
// provenance of every results file the CLI writes (SolveOptions::command). Set once by main().
#include <string>

namespace lightsolver::cli {

inline std::string& command_line() {
  static std::string text;
  return text;
}

/// argv joined by spaces; an argument with anything but [A-Za-z0-9_./:=,+-] in single quotes.
inline std::string quoted_command_line(int argc, char** argv) {
  std::string out;
  for (int i = 0; i < argc; ++i) {
    const std::string arg = argv[i];
    bool plain = !arg.empty();
    for (const char c : arg) {
      const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                      std::string("_./:=,+-").find(c) != std::string::npos;
      plain = plain && ok;
    }
    if (!out.empty()) out += ' ';
    if (plain) {
      out += arg;
      continue;
    }
    out += '\'';
    for (const char c : arg) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    out += '\'';
  }
  return out;
}

}  // namespace lightsolver::cli
