// The fast path of parse_json_text: see json_fast.hpp. The rules follow nlohmann 3.11's lexer:
// integers without fraction or exponent are number_unsigned (or number_integer when negative)
// while they fit in 64 bits, everything else a double; a later duplicate key replaces an earlier
// one; strings with escapes or non-ASCII bytes are decoded by nlohmann itself.
#include "io/json_fast.hpp"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <system_error>

namespace lightsolver::detail {
namespace {

class FastParser {
 public:
  explicit FastParser(std::string_view text) : p_(text.data()), end_(text.data() + text.size()) {}

  // The document, or false (leaving `out` unspecified) where nlohmann must decide.
  bool document(nlohmann::json& out) {
    skip_space();
    if (!value(out, 0)) return false;
    skip_space();
    return p_ == end_;
  }

 private:
  static constexpr int kMaxDepth = 256;

  void skip_space() {
    while (p_ != end_ && (*p_ == ' ' || *p_ == '\n' || *p_ == '\r' || *p_ == '\t')) ++p_;
  }

  bool literal(std::string_view word) {
    if (std::size_t(end_ - p_) < word.size() || std::string_view(p_, word.size()) != word)
      return false;
    p_ += word.size();
    return true;
  }

  bool value(nlohmann::json& out, int depth) {
    if (p_ == end_) return false;
    switch (*p_) {
      case '{':
        return depth < kMaxDepth && object(out, depth + 1);
      case '[':
        return depth < kMaxDepth && array(out, depth + 1);
      case '"': {
        std::string s;
        if (!string(s)) return false;
        out = std::move(s);
        return true;
      }
      case 't':
        out = true;
        return literal("true");
      case 'f':
        out = false;
        return literal("false");
      case 'n':
        out = nullptr;
        return literal("null");
      default:
        return number(out);
    }
  }

  bool object(nlohmann::json& out, int depth) {
    ++p_;  // '{'
    out = nlohmann::json::object();
    skip_space();
    if (p_ != end_ && *p_ == '}') {
      ++p_;
      return true;
    }
    for (;;) {
      skip_space();
      std::string key;
      if (p_ == end_ || *p_ != '"' || !string(key)) return false;
      skip_space();
      if (p_ == end_ || *p_ != ':') return false;
      ++p_;
      skip_space();
      if (!value(out[key], depth)) return false;  // a repeated key: the last value stands
      skip_space();
      if (p_ == end_) return false;
      if (*p_ == '}') {
        ++p_;
        return true;
      }
      if (*p_++ != ',') return false;
    }
  }

  bool array(nlohmann::json& out, int depth) {
    ++p_;  // '['
    out = nlohmann::json::array();
    skip_space();
    if (p_ != end_ && *p_ == ']') {
      ++p_;
      return true;
    }
    for (;;) {
      skip_space();
      nlohmann::json element;
      if (!value(element, depth)) return false;
      out.push_back(std::move(element));
      skip_space();
      if (p_ == end_) return false;
      if (*p_ == ']') {
        ++p_;
        return true;
      }
      if (*p_++ != ',') return false;
    }
  }

  // Plain ASCII without escapes here; anything else through nlohmann (its decoding and checks).
  bool string(std::string& out) {
    const char* start = p_++;  // the opening quote
    bool plain = true;
    for (; p_ != end_ && *p_ != '"'; ++p_) {
      const auto c = static_cast<unsigned char>(*p_);
      if (c == '\\') {
        plain = false;
        if (++p_ == end_) return false;
      } else if (c < 0x20 || c >= 0x80) {
        plain = false;
      }
    }
    if (p_ == end_) return false;
    ++p_;  // the closing quote
    if (plain) {
      out.assign(start + 1, p_ - 1);
      return true;
    }
    try {
      out = nlohmann::json::parse(std::string_view(start, p_ - start)).get<std::string>();
      return true;
    } catch (const nlohmann::json::exception&) {
      return false;
    }
  }

  static bool digit(char c) { return c >= '0' && c <= '9'; }

  // JSON's number grammar checked here; the value by from_chars (correctly rounded, as strtod).
  bool number(nlohmann::json& out) {
    const char* start = p_;
    if (p_ != end_ && *p_ == '-') ++p_;
    if (p_ == end_ || !digit(*p_)) return false;
    if (*p_ == '0') {
      ++p_;
    } else {
      while (p_ != end_ && digit(*p_)) ++p_;
    }
    bool integral = true;
    if (p_ != end_ && *p_ == '.') {
      integral = false;
      if (++p_ == end_ || !digit(*p_)) return false;
      while (p_ != end_ && digit(*p_)) ++p_;
    }
    if (p_ != end_ && (*p_ == 'e' || *p_ == 'E')) {
      integral = false;
      ++p_;
      if (p_ != end_ && (*p_ == '+' || *p_ == '-')) ++p_;
      if (p_ == end_ || !digit(*p_)) return false;
      while (p_ != end_ && digit(*p_)) ++p_;
    }
    if (integral) {
      if (*start == '-') {
        std::int64_t v = 0;
        const auto r = std::from_chars(start, p_, v);
        if (r.ec == std::errc() && r.ptr == p_) {
          out = v;
          return true;
        }
      } else {
        std::uint64_t v = 0;
        const auto r = std::from_chars(start, p_, v);
        if (r.ec == std::errc() && r.ptr == p_) {
          out = v;
          return true;
        }
      }
    }
    double v = 0.0;
    const auto r = std::from_chars(start, p_, v);
    if (r.ec != std::errc() || r.ptr != p_ || !std::isfinite(v)) return false;
    out = v;
    return true;
  }

  const char* p_;
  const char* end_;
};

}  // namespace

std::optional<nlohmann::json> parse_json_fast(std::string_view text) {
  if (!text.empty() && static_cast<unsigned char>(text.front()) == 0xEF) return std::nullopt;
  nlohmann::json doc;
  if (!FastParser(text).document(doc)) return std::nullopt;
  return doc;
}

}  // namespace lightsolver::detail
