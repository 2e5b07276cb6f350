// IES LM-63 parser: versions 1986, 1991, 1995, 2002 and 2019 (docs/photometry.md).

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include "photometry_internal.hpp"

namespace lightsolver {

namespace {

using photometry_detail::fail;
using photometry_detail::kAngleEps;
using photometry_detail::Line;
using photometry_detail::TokenStream;
using photometry_detail::trim;

constexpr double kFootToMetre = 0.3048;

bool near(double a, double b) { return std::abs(a - b) < kAngleEps; }

bool starts_with_ci(std::string_view s, std::string_view prefix) {
  if (s.size() < prefix.size()) return false;
  for (std::size_t i = 0; i < prefix.size(); ++i)
    if (std::toupper(static_cast<unsigned char>(s[i])) != prefix[i]) return false;
  return true;
}

std::string upper(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

// The version line; 1986 files have none (their first line is already a label).
int detect_year(std::string_view first) {
  first = trim(first);
  if (starts_with_ci(first, "IESNA:LM-63-1995")) return 1995;
  if (starts_with_ci(first, "IESNA:LM-63-2002")) return 2002;
  if (starts_with_ci(first, "IES:LM-63-2019") || starts_with_ci(first, "IESNA:LM-63-2019"))
    return 2019;
  if (starts_with_ci(first, "IESNA91") || starts_with_ci(first, "IESNA:LM-63-1991")) return 1991;
  return 1986;
}

bool is_tilt_line(std::string_view line) {
  line = trim(line);
  if (!starts_with_ci(line, "TILT")) return false;
  return trim(line.substr(4)).substr(0, 1) == "=";
}

// Keyword lines ("[TEST] 123", "[MORE] continues the previous one") up to the TILT line.
// Returns the index of the TILT line.
std::size_t read_labels(const std::vector<Line>& lines, std::size_t first, PhotometricData& data) {
  for (std::size_t i = first; i < lines.size(); ++i) {
    const std::string_view text = trim(lines[i].text);
    if (is_tilt_line(text)) return i;
    if (text.empty()) continue;
    std::string key, value(text);
    if (text.front() == '[') {
      const std::size_t close = text.find(']');
      if (close != std::string_view::npos) {
        key = upper(text.substr(1, close - 1));
        value = std::string(trim(text.substr(close + 1)));
      }
    }
    if (key == "MORE" && !data.keywords.empty()) {
      data.keywords.back().second += "\n" + value;
    } else {
      data.keywords.emplace_back(std::move(key), std::move(value));
    }
  }
  fail(data.source_file, lines.empty() ? 1 : lines.back().number,
       "missing TILT= line (LM-63 files name their tilt data before the photometric data)");
}

TiltData read_tilt(TokenStream& in) {
  TiltData tilt;
  tilt.lamp_geometry = static_cast<int>(in.integer("TILT lamp-to-luminaire geometry", 1, 3));
  const long n = in.integer("number of TILT angles", 1, 100000);
  for (long i = 0; i < n; ++i) {
    const double a = in.number("TILT angle");
    if (a < 0.0 || a > 180.0) fail(in.file(), in.last_line(), "TILT angles must lie in 0..180");
    if (!tilt.angles_deg.empty() && a <= tilt.angles_deg.back())
      fail(in.file(), in.last_line(), "TILT angles must increase");
    tilt.angles_deg.push_back(a);
  }
  for (long i = 0; i < n; ++i) {
    const double f = in.number("TILT multiplying factor");
    if (f < 0.0) fail(in.file(), in.last_line(), "TILT multiplying factors must be >= 0");
    tilt.factors.push_back(f);
  }
  return tilt;
}

// TILT=<file>: the file lies next to the IES file (or at an absolute path).
TiltData read_tilt_file(const std::string& name, const std::optional<std::string>& dir,
                        const std::string& ies_file, int line) {
  if (!dir) fail(ies_file, line, "TILT=" + name + " names a file, but the text has no directory");
  std::filesystem::path path(name);
  if (path.is_relative()) path = std::filesystem::path(*dir) / path;
  std::string text;
  try {
    text = photometry_detail::read_file(path.string());
  } catch (const InputError&) {
    fail(ies_file, line, "TILT file not found or unreadable: " + path.string());
  }
  const auto lines = photometry_detail::split_lines(text);
  TokenStream in(lines, 0, path.string());
  TiltData tilt = read_tilt(in);
  if (!in.at_end()) fail(in.file(), in.line(), "unexpected data after the TILT table");
  return tilt;
}

void read_tilt_section(TokenStream& in, const std::vector<Line>& lines, std::size_t tilt_line,
                       int year, const std::optional<std::string>& dir, PhotometricData& data) {
  const std::string_view text = trim(lines[tilt_line].text);
  const std::string value(trim(text.substr(text.find('=') + 1)));
  const int line = lines[tilt_line].number;
  const std::string key = upper(value);
  if (key == "NONE") {
    data.tilt = "NONE";
  } else if (key == "INCLUDE") {
    data.tilt = "INCLUDE";
    data.tilt_data = read_tilt(in);
  } else if (value.empty()) {
    fail(data.source_file, line, "TILT= needs NONE, INCLUDE or a file name");
  } else if (year >= 2019) {
    fail(data.source_file, line, "LM-63-2019 allows only TILT=NONE or TILT=INCLUDE");
  } else {
    data.tilt = value;
    data.tilt_data = read_tilt_file(value, dir, data.source_file, line);
  }
}

// Luminous opening from the signs of width, length and height (LM-63 tables, per version).
void decode_opening(double w, double l, double h, int year, PhotometricData& data) {
  const auto sign = [](double v) { return v < 0 ? '-' : (v == 0 ? '0' : '+'); };
  const std::string key{sign(l), sign(w), sign(h)};  // length, width, height
  const double al = std::abs(l), aw = std::abs(w), ah = std::abs(h);
  using S = OpeningShape;
  S shape = S::Rectangle;
  double len = al, wid = aw;
  if (key == "000") {
    shape = S::Point;
  } else if (key == "++0") {
    shape = S::Rectangle;
  } else if (key == "+++" || key == "0++" || key == "+0+") {
    shape = S::Box;
  } else if (year <= 1995 && (key == "0-0" || key == "0-+")) {  // circle of diameter |w|
    shape = key == "0-0" ? S::Disk : S::VerticalCylinder;
    len = aw;
  } else if (year <= 1991 && (key == "+-0" || key == "+-+")) {
    shape = key == "+-0" ? S::Disk : S::Sphere;
  } else if (year == 1995 && key == "0--") {
    shape = S::Sphere;
    len = aw;
  } else if (year == 1995 && (key == "+0-" || key == "0+-")) {
    shape = key == "+0-" ? S::HorizontalCylinderC0 : S::HorizontalCylinderC90;
    if (key == "+0-")
      wid = ah;
    else
      len = ah;
  } else if (year == 1995 && (key == "-++" || key == "+-+")) {
    shape = S::VerticalCylinder;
  } else if (year == 1995 && (key == "-+-" || key == "+--")) {
    shape = S::Sphere;
  } else if (year >= 2002 && (key == "--0" || key == "--+" || key == "---")) {
    shape = key == "--0" ? S::Disk : (key == "--+" ? S::VerticalCylinder : S::Sphere);
  } else if (year >= 2002 && (key == "+--" || key == "-+-")) {
    shape = key == "+--" ? S::HorizontalCylinderC0 : S::HorizontalCylinderC90;
  } else if (year >= 2002 && key == "-0-") {
    shape = S::VerticalDisk;
    len = 0.0;
    wid = al;
  } else {
    data.warnings.push_back("luminous opening (width " + photometry_detail::format_number(w) +
                            ", length " + photometry_detail::format_number(l) + ", height " +
                            photometry_detail::format_number(h) +
                            ") matches no LM-63 shape; using a rectangle of |length| x |width|");
  }
  data.opening_shape = shape;
  data.opening_length_m = len;
  data.opening_width_m = wid;
  data.opening_height_m = ah;
}

std::vector<double> read_angles(TokenStream& in, long n, const char* what, double lo, double hi,
                                int& first_line) {
  std::vector<double> angles;
  angles.reserve(static_cast<std::size_t>(n));
  for (long i = 0; i < n; ++i) {
    const double a = in.number(what);
    if (i == 0) first_line = in.last_line();
    if (a < lo - kAngleEps || a > hi + kAngleEps)
      fail(in.file(), in.last_line(),
           std::string(what) + " " + photometry_detail::format_number(a) + " is outside " +
               photometry_detail::format_number(lo) + ".." + photometry_detail::format_number(hi));
    if (!angles.empty() && a <= angles.back() + kAngleEps)
      fail(in.file(), in.last_line(),
           std::string(what) + "s must increase (" +
               photometry_detail::format_number(angles.back()) + " then " +
               photometry_detail::format_number(a) + ")");
    angles.push_back(a);
  }
  return angles;
}

PhotometricSymmetry classify_horizontal(PhotometricType type, const std::vector<double>& h,
                                        const std::string& file, int line) {
  if (type != PhotometricType::C) {
    if (h.size() < 2)
      fail(file, line, "type A and B photometry needs at least 2 horizontal angles");
    return near(h.front(), 0.0) ? PhotometricSymmetry::LateralAB : PhotometricSymmetry::None;
  }
  if (h.size() == 1) return PhotometricSymmetry::Rotational;
  const double first = h.front(), last = h.back();
  if (near(first, 0.0) && near(last, 90.0)) return PhotometricSymmetry::Quadrant;
  if (near(first, 0.0) && near(last, 180.0)) return PhotometricSymmetry::BilateralC0C180;
  if (near(first, 90.0) && near(last, 270.0)) return PhotometricSymmetry::BilateralC90C270;
  if (near(first, 0.0) && last > 180.0) return PhotometricSymmetry::None;
  fail(file, line,
       "type C horizontal angles must run 0, 0-90, 0-180, 0-360 or 90-270 (got " +
           photometry_detail::format_number(first) + " to " +
           photometry_detail::format_number(last) + ")");
}

// Angle ranges per type: the polar coordinate must stay within a half circle.
void angle_limits(PhotometricType type, double& v_lo, double& v_hi, double& h_lo, double& h_hi) {
  switch (type) {
    case PhotometricType::C:
      v_lo = 0, v_hi = 180, h_lo = 0, h_hi = 360;
      break;
    case PhotometricType::A:
      v_lo = -90, v_hi = 90, h_lo = -180, h_hi = 180;
      break;
    case PhotometricType::B:
      v_lo = -180, v_hi = 180, h_lo = -90, h_hi = 90;
      break;
  }
}

void read_photometry(TokenStream& in, int year, PhotometricData& data) {
  const std::string& file = data.source_file;
  const long lamps = in.integer("number of lamps", 0, 1000000);
  const double lumens = in.number("lumens per lamp");
  const int lumens_line = in.last_line();
  const double multiplier = in.number("candela multiplier");
  if (!(multiplier > 0.0)) fail(file, in.last_line(), "candela multiplier must be > 0");
  const long nv = in.integer("number of vertical angles", 2, kMaxPhotometricValues);
  const long nh = in.integer("number of horizontal angles", 1, kMaxPhotometricValues);
  if (static_cast<std::size_t>(nv) * static_cast<std::size_t>(nh) > kMaxPhotometricValues)
    fail(file, in.last_line(),
         "candela table of " + std::to_string(nv) + " x " + std::to_string(nh) +
             " values is larger than the " + std::to_string(kMaxPhotometricValues) + " accepted");
  const double type_code = in.number("photometric type");
  if (type_code != 1.0 && type_code != 2.0 && type_code != 3.0)
    fail(file, in.last_line(), "unknown photometric type (must be 1 = C, 2 = B or 3 = A)");
  const auto type = type_code == 1.0 ? PhotometricType::C
                                     : (type_code == 2.0 ? PhotometricType::B : PhotometricType::A);
  const double units = in.number("units type");
  if (units != 1.0 && units != 2.0)
    fail(file, in.last_line(), "units type must be 1 (feet) or 2 (metres)");
  const double to_m = units == 1.0 ? kFootToMetre : 1.0;
  const double width = in.number("luminous opening width") * to_m;
  const double length = in.number("luminous opening length") * to_m;
  const double height = in.number("luminous opening height") * to_m;
  data.ballast_factor = in.number("ballast factor");
  if (!(data.ballast_factor > 0.0)) fail(file, in.last_line(), "ballast factor must be > 0");
  const double third = in.number(year >= 2019 ? "file generation type" : "ballast-lamp factor");
  if (year <= 1995 && !(third > 0.0)) fail(file, in.last_line(), "ballast-lamp factor must be > 0");
  data.input_watts = in.number("input watts");

  if (lumens == -1.0) {
    data.absolute_photometry = true;
  } else if (!(lumens > 0.0)) {
    fail(file, lumens_line, "lumens per lamp must be > 0, or -1 for absolute photometry");
  } else if (lamps < 1) {
    fail(file, lumens_line, "number of lamps must be >= 1");
  }
  data.lamp_count = static_cast<int>(lamps);
  data.rated_lumens_lm = data.absolute_photometry ? 0.0 : static_cast<double>(lamps) * lumens;
  data.candela_multiplier = multiplier;
  if (year >= 2019) data.file_generation_type = third;
  if (year <= 1995) data.ballast_lamp_factor = third;
  decode_opening(width, length, height, year, data);

  photometry_detail::StoredTable table;
  table.type = data.type = type;
  double v_lo, v_hi, h_lo, h_hi;
  angle_limits(type, v_lo, v_hi, h_lo, h_hi);
  int v_line = 0, h_line = 0;
  table.vertical_deg = read_angles(in, nv, "vertical angle", v_lo, v_hi, v_line);
  table.horizontal_deg = read_angles(in, nh, "horizontal angle", h_lo, h_hi, h_line);
  table.symmetry = data.symmetry = classify_horizontal(type, table.horizontal_deg, file, h_line);

  const double factor = multiplier * data.ballast_factor * data.ballast_lamp_factor;
  table.candela.reserve(static_cast<std::size_t>(nv * nh));
  for (long i = 0; i < nv * nh; ++i) {
    const double cd = in.number("candela value");
    if (cd < 0.0) fail(file, in.last_line(), "candela values must be >= 0");
    if (!std::isfinite(cd * factor)) fail(file, in.last_line(), "candela value is too large");
    table.candela.push_back(cd * factor);
  }
  if (!in.at_end())
    fail(file, in.line(),
         "unexpected data after the candela table (do the angle counts match the values?)");
  photometry_detail::unfold(table, data);
}

}  // namespace

PhotometricData parse_ies(std::string_view text, const std::string& source_name,
                          const std::optional<std::string>& tilt_directory) {
  PhotometricData data;
  data.source_file = source_name;
  data.format = PhotometricFormat::Ies;
  const auto lines = photometry_detail::split_lines(text);
  if (lines.empty()) fail(source_name, 1, "empty file");
  const int year = detect_year(lines.front().text);
  data.format_version = "LM-63-" + std::to_string(year);
  const std::size_t tilt_line = read_labels(lines, year == 1986 ? 0 : 1, data);
  TokenStream in(lines, tilt_line + 1, source_name);
  read_tilt_section(in, lines, tilt_line, year, tilt_directory, data);
  read_photometry(in, year, data);
  return data;
}

}  // namespace lightsolver
