#include "io/json_reader.hpp"

#include <cmath>
#include <optional>

#include "io/json_fast.hpp"

namespace lightsolver::detail {

std::string JsonNode::describe() const {
  if (j_.is_number()) return "a number";
  return std::string("a") + (j_.is_object() || j_.is_array() ? "n " : " ") + j_.type_name();
}

const nlohmann::json& JsonNode::object() const {
  if (!j_.is_object()) fail("expected an object, got " + describe());
  return j_;
}

JsonNode JsonNode::at(const char* key) const {
  object();
  if (!j_.contains(key)) fail(std::string("missing required key \"") + key + "\"");
  return JsonNode(j_.at(key), path_.empty() ? key : path_ + "." + key, file_);
}

JsonNode JsonNode::operator[](std::size_t i) const {
  return JsonNode(j_.at(i), path_ + "[" + std::to_string(i) + "]", file_);
}

std::size_t JsonNode::array_size() const {
  if (!j_.is_array()) fail("expected an array, got " + describe());
  return j_.size();
}

void JsonNode::require_object(std::initializer_list<const char*> allowed) const {
  require_object(std::span<const char* const>(allowed.begin(), allowed.size()));
}

void JsonNode::require_object(std::span<const char* const> allowed) const {
  for (const auto& item : object().items()) {
    bool known = false;
    for (const char* k : allowed) known = known || item.key() == k;
    if (!known) {
      std::string list;
      for (const char* k : allowed) list += (list.empty() ? "" : ", ") + std::string(k);
      throw InputError(file_, path_.empty() ? item.key() : path_ + "." + item.key(),
                       "unknown key (allowed here: " + list + ")");
    }
  }
}

double JsonNode::number() const {
  if (!j_.is_number()) fail("expected a number, got " + describe());
  const double v = j_.get<double>();
  if (!std::isfinite(v)) fail("must be a finite number");
  return v;
}

std::uint64_t JsonNode::unsigned_integer() const {
  if (j_.is_number_unsigned()) return j_.get<std::uint64_t>();
  if (j_.is_number_integer())
    fail("must be >= 0 (got " + std::to_string(j_.get<long long>()) + ")");
  if (j_.is_number_float()) {
    const double v = j_.get<double>();
    if (v >= 0 && v == std::floor(v) && v < 1.8e19) return static_cast<std::uint64_t>(v);
    fail("expected a non-negative integer, got " + j_.dump());
  }
  fail("expected a non-negative integer, got " + describe());
}

std::string JsonNode::string() const {
  if (!j_.is_string()) fail("expected a string, got " + describe());
  return j_.get<std::string>();
}

bool JsonNode::boolean() const {
  if (!j_.is_boolean()) fail("expected true or false, got " + describe());
  return j_.get<bool>();
}

glm::dvec3 JsonNode::vec3() const {
  if (array_size() != 3) fail("expected [x, y, z] (3 numbers), got " + std::to_string(j_.size()));
  return {(*this)[0].number(), (*this)[1].number(), (*this)[2].number()};
}

nlohmann::json parse_json_text(const std::string& text, const std::string& file) {
  if (std::optional<nlohmann::json> doc = parse_json_fast(text)) return std::move(*doc);
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    std::size_t line = 1, column = 1;
    const std::size_t end = std::min<std::size_t>(e.byte > 0 ? e.byte - 1 : 0, text.size());
    for (std::size_t i = 0; i < end; ++i) {
      if (text[i] == '\n') {
        ++line;
        column = 1;
      } else {
        ++column;
      }
    }
    std::string what = e.what();
    const auto pos = what.find("syntax error");
    throw InputError(file, "line " + std::to_string(line) + ", column " + std::to_string(column),
                     "malformed JSON: " + (pos == std::string::npos ? what : what.substr(pos)));
  } catch (const nlohmann::json::exception& e) {  // e.g. a number too large for a double
    std::string what = e.what();
    const auto pos = what.find("] ");
    throw InputError(file, "",
                     "malformed JSON: " + (pos == std::string::npos ? what : what.substr(pos + 2)));
  }
}

}  // namespace lightsolver::detail
