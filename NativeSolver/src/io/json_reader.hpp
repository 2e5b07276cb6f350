#pragma once
// A typed, path-tracking view of a JSON value, so every loader error can say exactly which
// field of which file is wrong ("office.json: luminaires[2].flux_lm: expected a number").

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <initializer_list>
#include <span>
#include <string>

#include "lightsolver/error.hpp"

namespace lightsolver::detail {

class JsonNode {
 public:
  JsonNode(const nlohmann::json& j, std::string path, const std::string& file)
      : j_(j), path_(std::move(path)), file_(file) {}

  [[noreturn]] void fail(const std::string& what) const { throw InputError(file_, path_, what); }

  const std::string& path() const { return path_; }
  const std::string& file() const { return file_; }
  bool has(const char* key) const { return j_.is_object() && j_.contains(key); }
  bool is_null() const { return j_.is_null(); }
  JsonNode at(const char* key) const;                    // required member
  JsonNode operator[](std::size_t i) const;              // array element
  std::size_t array_size() const;                        // fails unless an array
  void require_object(std::initializer_list<const char*> allowed) const;  // no unknown keys
  void require_object(std::span<const char* const> allowed) const;       // no unknown keys
  const nlohmann::json& object() const;                  // fails unless an object
  const nlohmann::json& json() const { return j_; }      // the value itself, for fast paths

  double number() const;  // finite number
  std::uint64_t unsigned_integer() const;
  std::string string() const;
  bool boolean() const;
  glm::dvec3 vec3() const;

  // Optional members with defaults.
  double number_or(const char* key, double fallback) const {
    return has(key) ? at(key).number() : fallback;
  }
  bool boolean_or(const char* key, bool fallback) const {
    return has(key) ? at(key).boolean() : fallback;
  }

 private:
  std::string describe() const;  // the JSON type, for "expected X, got Y"
  const nlohmann::json& j_;
  std::string path_;
  const std::string& file_;
};

// Parses text, turning nlohmann's byte offsets into "line L, column C" messages.
nlohmann::json parse_json_text(const std::string& text, const std::string& file);

}  // namespace lightsolver::detail
