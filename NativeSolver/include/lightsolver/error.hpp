#pragma once
/// \file error.hpp
/// Errors and warnings about user input. Every message names where the problem is: the file,
/// and the field (a JSON path such as `luminaires[2].flux_lm`) or the line.

#include <stdexcept>
#include <string>
#include <vector>

namespace lightsolver {

/// Bad input that stops a run: a malformed file, an impossible value, a dangling reference.
class InputError : public std::runtime_error {
 public:
  /// \param file   file the problem is in (may be empty for in-memory scenes)
  /// \param where  JSON path ("meshes[1].vertices[7]") or "line 12"
  /// \param what   what is wrong, in words a user can act on
  InputError(std::string file, std::string where, const std::string& what)
      : std::runtime_error(format(file, where, what)),
        file_(std::move(file)),
        where_(std::move(where)) {}

  const std::string& file() const { return file_; }
  const std::string& where() const { return where_; }

 private:
  static std::string format(const std::string& file, const std::string& where,
                            const std::string& what) {
    std::string s = file.empty() ? std::string("<scene>") : file;
    if (!where.empty()) s += ": " + where;
    return s + ": " + what;
  }
  std::string file_, where_;
};

/// Non-fatal remarks collected while loading or solving (dropped triangles, capped paths…).
using Warnings = std::vector<std::string>;

}  // namespace lightsolver
