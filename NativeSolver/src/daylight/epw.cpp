// EPW weather files (docs/daylight.md, "Weather"), after the EnergyPlus data dictionary: a
// LOCATION line, header lines up to DATA PERIODS, then one row of 35 fields per hour.
#include "daylight/epw.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <sstream>

#include "daylight/sun_position.hpp"
#include "lightsolver/error.hpp"
#include "lightsolver/weather.hpp"

namespace lightsolver {
namespace {

namespace f = detail::epw;

constexpr const char* kFieldNames[] = {"year",
                                       "month",
                                       "day",
                                       "hour",
                                       "minute",
                                       "data source flags",
                                       "dry bulb temperature",
                                       "dew point temperature",
                                       "relative humidity",
                                       "atmospheric pressure",
                                       "extraterrestrial horizontal radiation",
                                       "extraterrestrial direct normal radiation",
                                       "horizontal infrared radiation",
                                       "global horizontal radiation",
                                       "direct normal radiation",
                                       "diffuse horizontal radiation",
                                       "global horizontal illuminance",
                                       "direct normal illuminance",
                                       "diffuse horizontal illuminance"};

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> out;
  size_t start = 0;
  while (true) {
    const size_t comma = line.find(',', start);
    out.push_back(line.substr(start, comma == std::string_view::npos ? comma : comma - start));
    if (comma == std::string_view::npos) return out;
    start = comma + 1;
  }
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
    s.remove_suffix(1);
  return s;
}

class Reader {
 public:
  Reader(std::string_view text, std::string file) : text_(text), file_(std::move(file)) {}

  WeatherFile read() {
    WeatherFile w;
    w.file = file_;
    std::string_view line;
    if (!next(line))
      throw InputError(file_, "", "the file is empty: an EPW file starts with its LOCATION line");
    w.location = location(line);
    bool leap = false;
    while (true) {
      if (!next(line)) fail("no DATA PERIODS line: the header ends with it, then the hours");
      const auto fields = split(line);
      const std::string_view key = trim(fields[0]);
      if (key == "HOLIDAYS/DAYLIGHT SAVINGS" && fields.size() > 1)
        leap = trim(fields[1]) == "Yes" || trim(fields[1]) == "yes";
      if (key == "DATA PERIODS") break;
    }
    const int year_hours = leap ? 8784 : 8760;
    while (next(line)) {
      if (trim(line).empty()) continue;
      w.hours.push_back(hour_row(line, w.hours.empty() ? nullptr : &w.hours.back(), leap));
    }
    if (static_cast<int>(w.hours.size()) != year_hours)
      fail(std::to_string(w.hours.size()) + " hourly rows after DATA PERIODS; a year is " +
           std::to_string(year_hours) + (leap ? " (the header declares a leap year)" : ""));
    return w;
  }

 private:
  bool next(std::string_view& line) {
    if (pos_ >= text_.size()) return false;
    const size_t end = text_.find('\n', pos_);
    line = text_.substr(pos_, end == std::string_view::npos ? end : end - pos_);
    pos_ = end == std::string_view::npos ? text_.size() : end + 1;
    ++line_;
    return true;
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(file_, "line " + std::to_string(line_), what);
  }

  double number(std::string_view field, const std::string& name) const {
    field = trim(field);
    double v = 0.0;
    const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), v);
    if (field.empty() || ec != std::errc() || end != field.data() + field.size() ||
        !std::isfinite(v))
      fail(name + ": '" + std::string(field) + "' is not a number");
    return v;
  }

  double in_range(double v, double lo, double hi, const std::string& name) const {
    if (v < lo || v > hi) {
      std::ostringstream s;
      s << name << " " << v << " is outside " << lo << " … " << hi;
      fail(s.str());
    }
    return v;
  }

  WeatherLocation location(std::string_view line) const {
    const auto fields = split(line);
    if (trim(fields[0]) != "LOCATION")
      fail("an EPW file starts with its LOCATION line, found '" + std::string(line.substr(0, 40)) +
           "'");
    if (fields.size() != 10)
      fail("the LOCATION line has " + std::to_string(fields.size()) +
           " fields; it needs 10 (LOCATION, city, region, country, source, WMO, latitude, "
           "longitude, time zone, elevation)");
    WeatherLocation l;
    l.city = trim(fields[1]);
    l.region = trim(fields[2]);
    l.country = trim(fields[3]);
    l.source = trim(fields[4]);
    l.wmo = trim(fields[5]);
    l.latitude_deg = in_range(number(fields[6], "latitude"), -90, 90, "latitude");
    l.longitude_deg = in_range(number(fields[7], "longitude"), -180, 180, "longitude");
    l.utc_offset_h = in_range(number(fields[8], "time zone"), -12, 14, "time zone");
    l.elevation_m = in_range(number(fields[9], "elevation"), -1000, 9999.9, "elevation");
    return l;
  }

  // A value of a daylight column: absent at or above the dictionary's missing mark.
  std::optional<double> value(const std::vector<std::string_view>& fields, int column,
                              double missing) const {
    const std::string name = kFieldNames[column];
    const double v = number(fields[column], name);
    if (v >= missing) return std::nullopt;
    return in_range(v, 0.0, missing, name);
  }

  WeatherHour hour_row(std::string_view line, const WeatherHour* previous, bool leap) const {
    const auto fields = split(trim(line));
    if (static_cast<int>(fields.size()) != f::kFields)
      fail("an hourly row has " + std::to_string(f::kFields) +
           " comma-separated fields, this "
           "one " +
           std::to_string(fields.size()) + " (a truncated or damaged file?)");
    WeatherHour h;
    h.line = line_;
    h.year = static_cast<int>(in_range(number(fields[0], "year"), -9999, 9999, "year"));
    h.month = static_cast<int>(in_range(number(fields[f::kMonth], "month"), 1, 12, "month"));
    const int days = detail::days_in_month(leap ? 2000 : 2001, h.month);
    h.day = static_cast<int>(in_range(number(fields[f::kDay], "day"), 1, days, "day"));
    h.hour = static_cast<int>(in_range(number(fields[f::kHour], "hour"), 1, 24, "hour"));
    check_order(h, previous, leap);
    h.direct_normal_w_m2 = value(fields, f::kDirectNormalIrradiance, f::kMissingIrradiance);
    h.diffuse_horizontal_w_m2 =
        value(fields, f::kDiffuseHorizontalIrradiance, f::kMissingIrradiance);
    h.global_horizontal_lx = value(fields, f::kGlobalHorizontalIlluminance, f::kMissingIlluminance);
    h.direct_normal_lx = value(fields, f::kDirectNormalIlluminance, f::kMissingIlluminance);
    h.diffuse_horizontal_lx =
        value(fields, f::kDiffuseHorizontalIlluminance, f::kMissingIlluminance);
    return h;
  }

  // Rows run hour by hour from 1 January, hour 1.
  void check_order(const WeatherHour& h, const WeatherHour* p, bool leap) const {
    int month = 1, day = 1, hour = 1;
    if (p) {
      month = p->month, day = p->day, hour = p->hour + 1;
      if (hour > 24) hour = 1, ++day;
      if (day > detail::days_in_month(leap ? 2000 : 2001, month)) day = 1, ++month;
    }
    if (h.month != month || h.day != day || h.hour != hour)
      fail("rows run hour by hour through the year: expected month " + std::to_string(month) +
           ", day " + std::to_string(day) + ", hour " + std::to_string(hour) + ", found " +
           std::to_string(h.month) + "/" + std::to_string(h.day) + " hour " +
           std::to_string(h.hour));
  }

  std::string_view text_;
  std::string file_;
  size_t pos_ = 0;
  int line_ = 0;
};

}  // namespace

WeatherFile parse_epw(std::string_view text, const std::string& file) {
  return Reader(text, file).read();
}

WeatherFile read_epw(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), "", "cannot open the weather file");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_epw(text.str(), path.string());
}

std::vector<std::uint8_t> en17037_daylight_hours(const std::vector<double>& diffuse_horizontal_lx) {
  const std::size_t n = diffuse_horizontal_lx.size();
  for (std::size_t i = 0; i < n; ++i) {
    const double v = diffuse_horizontal_lx[i];
    if (!(v >= 0.0 && std::isfinite(v)))
      throw InputError("", "diffuse_horizontal_lx[" + std::to_string(i) + "]",
                       "an illuminance must be a finite number >= 0");
  }
  if (n < 2) throw InputError("", "diffuse_horizontal_lx", "fewer than 2 hours: no daylight hours");
  // The brighter half, ties taken in the order of the hours (a stable sort), so the mask is
  // the same on every platform.
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return diffuse_horizontal_lx[a] > diffuse_horizontal_lx[b];
  });
  std::vector<std::uint8_t> mask(n, 0);
  for (std::size_t i = 0; i < n / 2; ++i) mask[order[i]] = 1;
  return mask;
}

double median_external_diffuse_illuminance(const WeatherFile& weather) {
  std::vector<double> lux;
  lux.reserve(weather.hours.size());
  for (const WeatherHour& h : weather.hours) {
    if (!h.diffuse_horizontal_lx)
      throw InputError(weather.file, "line " + std::to_string(h.line),
                       "diffuse horizontal illuminance is missing (999999): the median "
                       "external diffuse illuminance needs every hour's");
    lux.push_back(*h.diffuse_horizontal_lx);
  }
  if (lux.size() < 2)
    throw InputError(weather.file, "", "no hours to take the median diffuse illuminance of");
  // The median over the daylight hours (the brighter half): the mean of the middle two (or
  // the middle one) of them, sorted.
  const std::vector<std::uint8_t> daylight = en17037_daylight_hours(lux);
  std::vector<double> bright;
  for (std::size_t i = 0; i < lux.size(); ++i)
    if (daylight[i]) bright.push_back(lux[i]);
  std::sort(bright.begin(), bright.end());
  const std::size_t half = bright.size(), mid = half / 2;
  return half % 2 == 0 ? 0.5 * (bright[mid - 1] + bright[mid]) : bright[mid];
}

}  // namespace lightsolver
