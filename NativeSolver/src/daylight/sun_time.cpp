// ISO 8601 date-times for the sun's position (lightsolver/daylight.hpp: parse_iso8601).
#include <charconv>
#include <cmath>
#include <optional>
#include <string>

#include "daylight/sun_position.hpp"
#include "lightsolver/daylight.hpp"
#include "lightsolver/error.hpp"

namespace lightsolver {
namespace {

// Reads exactly `digits` decimal digits at `pos`, or nothing.
std::optional<int> digits_at(std::string_view s, size_t pos, size_t digits) {
  if (pos + digits > s.size()) return std::nullopt;
  int v = 0;
  for (size_t i = pos; i < pos + digits; ++i) {
    if (s[i] < '0' || s[i] > '9') return std::nullopt;
    v = v * 10 + (s[i] - '0');
  }
  return v;
}

class Iso8601 {
 public:
  Iso8601(std::string_view text, const std::string& field) : s_(text), field_(field) {}

  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(detail::kSunInputs, field_,
                     "'" + std::string(s_) +
                         "' is not an ISO 8601 date-time "
                         "(YYYY-MM-DDThh:mm[:ss][Z|±hh:mm]): " +
                         what);
  }

  int number(size_t pos, size_t n, const char* name) const {
    auto v = digits_at(s_, pos, n);
    if (!v) fail(std::string("expected ") + std::to_string(n) + " digits for the " + name);
    return *v;
  }

  void expect(size_t pos, const char* chars, const char* what) const {
    if (pos >= s_.size() || std::string_view(chars).find(s_[pos]) == std::string_view::npos)
      fail(std::string("expected ") + what);
  }

  void range(int v, int lo, int hi, const char* name) const {
    if (v < lo || v > hi)
      fail(std::string(name) + " " + std::to_string(v) + " is outside " + std::to_string(lo) +
           " … " + std::to_string(hi));
  }

  CivilTime parse(std::optional<double> utc_offset_h) const {
    CivilTime t;
    t.year = number(0, 4, "year");
    expect(4, "-", "'-' after the year");
    t.month = number(5, 2, "month");
    range(t.month, 1, 12, "month");
    expect(7, "-", "'-' after the month");
    t.day = number(8, 2, "day");
    range(t.day, 1, detail::days_in_month(t.year, t.month), "day");
    expect(10, "T ", "'T' between date and time");
    t.hour = number(11, 2, "hour");
    range(t.hour, 0, 23, "hour");
    expect(13, ":", "':' after the hour");
    t.minute = number(14, 2, "minute");
    range(t.minute, 0, 59, "minute");
    size_t pos = 16;
    if (pos < s_.size() && s_[pos] == ':') {
      t.second = number(pos + 1, 2, "second");
      pos += 3;
      if (pos < s_.size() && (s_[pos] == '.' || s_[pos] == ',')) {
        size_t end = pos + 1;
        while (end < s_.size() && s_[end] >= '0' && s_[end] <= '9') ++end;
        if (end == pos + 1) fail("expected digits after the decimal mark");
        t.second += std::stod("0." + std::string(s_.substr(pos + 1, end - pos - 1)));
        pos = end;
      }
      if (t.second >= 61) fail("second " + std::to_string(t.second) + " is 61 or more");
    }
    std::optional<double> zone = read_zone(pos);
    if (zone && utc_offset_h && std::abs(*zone - *utc_offset_h) > 1e-9)
      throw InputError(
          detail::kSunInputs, field_,
          "'" + std::string(s_) + "': its zone disagrees with the time zone given beside it");
    if (!zone && !utc_offset_h)
      throw InputError(detail::kSunInputs, field_,
                       "'" + std::string(s_) + "' has no time zone: add Z (UTC) or ±hh:mm");
    t.utc_offset_h = zone ? *zone : *utc_offset_h;
    if (!std::isfinite(t.utc_offset_h) || std::abs(t.utc_offset_h) > 14)
      fail("the time zone must be −14 … 14 h");
    return t;
  }

 private:
  std::optional<double> read_zone(size_t pos) const {
    if (pos == s_.size()) return std::nullopt;
    if (s_[pos] == 'Z' && pos + 1 == s_.size()) return 0.0;
    expect(pos, "+-", "the end, 'Z' or ±hh:mm after the time");
    const double sign = s_[pos] == '-' ? -1.0 : 1.0;
    const int hours = number(pos + 1, 2, "zone's hours");
    int minutes = 0;
    size_t end = pos + 3;
    if (end < s_.size()) {
      if (s_[end] == ':') ++end;
      minutes = number(end, 2, "zone's minutes");
      range(minutes, 0, 59, "zone's minutes");
      end += 2;
    }
    if (end != s_.size()) fail("unexpected text after the zone");
    return sign * (hours + minutes / 60.0);
  }

  std::string_view s_;
  const std::string& field_;
};

}  // namespace

CivilTime parse_iso8601(std::string_view text, std::optional<double> utc_offset_h,
                        const std::string& field) {
  return Iso8601(text, field).parse(utc_offset_h);
}

}  // namespace lightsolver
