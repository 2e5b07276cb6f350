// EULUMDAT (.ldt) parser: one field per line, intensities in cd per 1000 lamp lumens.

#include <algorithm>
#include <cmath>

#include "photometry_internal.hpp"

namespace lightsolver {

namespace {

using photometry_detail::fail;
using photometry_detail::kAngleEps;
using photometry_detail::Line;
using photometry_detail::trim;

constexpr long kMaxPlanes = 100000;

// Reads the file line by line; every field is one line (the format has no separators).
class LineReader {
 public:
  LineReader(const std::vector<Line>& lines, std::string file)
      : lines_(lines), file_(std::move(file)) {}

  std::string text(const char* what) { return std::string(trim(next(what).text)); }

  double number(const char* what) {
    const Line& line = next(what);
    const std::string_view token = trim(line.text);
    double value = 0.0;
    if (!photometry_detail::parse_number(token, value, /*comma_decimal=*/true))
      fail(file_, line.number,
           std::string(what) + ": " + photometry_detail::quote(token) +
               " is not a finite number (EULUMDAT has one value per line)");
    last_line_ = line.number;
    return value;
  }

  long integer(const char* what, long lo, long hi) {
    const double v = number(what);
    if (v != std::floor(v) || v < static_cast<double>(lo) || v > static_cast<double>(hi))
      fail(file_, last_line_,
           std::string(what) + " must be a whole number in " +
               photometry_detail::format_number(lo) + ".." + photometry_detail::format_number(hi) +
               " (got " + photometry_detail::format_number(v) + ")");
    return static_cast<long>(v);
  }

  // Only blank lines may follow the intensities.
  void expect_end() {
    for (; index_ < lines_.size(); ++index_)
      if (!trim(lines_[index_].text).empty())
        fail(file_, lines_[index_].number,
             "unexpected data after the intensity table (do Mc, Ng and Isym match the values?)");
  }

  int last_line() const { return last_line_; }
  const std::string& file() const { return file_; }

 private:
  const Line& next(const char* what) {
    if (index_ >= lines_.size())
      fail(file_, lines_.empty() ? 1 : lines_.back().number,
           std::string("file ends where the ") + what + " should be (truncated data?)");
    last_line_ = lines_[index_].number;
    return lines_[index_++];
  }

  const std::vector<Line>& lines_;
  std::string file_;
  std::size_t index_ = 0;
  int last_line_ = 0;
};

struct LampSets {
  double flux_lm = 0.0;
  bool absolute = false;
  int lamps = 0;
  std::string types;
  int flux_line = 0;
  double watts = 0.0;  ///< sum of the sets' wattage including ballast (0: not stated)
};

// Field 26 and its n-line groups 26a..26f (grouped by field: all counts, then all types...).
LampSets read_lamp_sets(LineReader& in) {
  const long n = in.integer("number of lamp sets", 1, 1000);
  LampSets sets;
  for (long i = 0; i < n; ++i) {
    const long count = in.integer("number of lamps", -1000000, 1000000);
    sets.absolute = sets.absolute || count < 0;  // negative count marks absolute photometry
    sets.lamps += static_cast<int>(std::abs(count));
  }
  for (long i = 0; i < n; ++i) sets.types += (i ? "; " : "") + in.text("type of lamps");
  for (long i = 0; i < n; ++i) {
    const double flux = in.number("total luminous flux of lamps");
    if (flux < 0.0) fail(in.file(), in.last_line(), "lamp flux must be >= 0");
    sets.flux_lm += flux;
    sets.flux_line = in.last_line();
  }
  for (long i = 0; i < n; ++i) in.text("colour temperature");
  for (long i = 0; i < n; ++i) in.text("colour rendering index");
  // Field 26f, "wattage including ballast" per set: the luminaire's input power (the report
  // prints it where the scene gives no power_w). A negative one is no power at all.
  for (long i = 0; i < n; ++i) sets.watts += std::max(0.0, in.number("lamp wattage"));
  return sets;
}

std::vector<double> read_angles(LineReader& in, long n, const char* what, double hi) {
  std::vector<double> angles;
  for (long i = 0; i < n; ++i) {
    const double a = in.number(what);
    if (a < -kAngleEps || a > hi + kAngleEps)
      fail(in.file(), in.last_line(),
           std::string(what) + " " + photometry_detail::format_number(a) + " is outside 0.." +
               photometry_detail::format_number(hi));
    if (!angles.empty() && a <= angles.back() + kAngleEps)
      fail(in.file(), in.last_line(), std::string(what) + "s must increase");
    angles.push_back(a);
  }
  return angles;
}

// First stored plane and plane count for symmetry indicator Isym (EULUMDAT Mc1..Mc2).
void stored_planes(long isym, long mc, const std::vector<double>& c, const std::string& file,
                   int line, long& first, long& count) {
  const auto need = [&](bool ok, const char* what) {
    if (!ok) fail(file, line, std::string("Isym ") + std::to_string(isym) + ": " + what);
  };
  const auto angle_is = [&](long i, double a) { return std::abs(c[i] - a) < kAngleEps; };
  need(angle_is(0, 0.0), "the C angles must start at 0");
  switch (isym) {
    case 0:
      first = 0, count = mc;
      need(mc >= 2, "needs at least 2 C planes");
      break;
    case 1:
      first = 0, count = 1;
      break;
    case 2:
      need(mc % 2 == 0 && angle_is(mc / 2, 180.0), "needs an even Mc with C(Mc/2) = 180");
      first = 0, count = mc / 2 + 1;
      break;
    case 3:  // planes C270 .. C360 = C0 .. C90, wrapping (Mc1 = 3 Mc / 4 + 1)
      need(mc % 4 == 0 && angle_is(mc / 4, 90.0) && angle_is(3 * mc / 4, 270.0),
           "needs Mc divisible by 4 with C(Mc/4) = 90 and C(3Mc/4) = 270");
      first = 3 * mc / 4, count = mc / 2 + 1;
      break;
    default:
      need(mc % 4 == 0 && angle_is(mc / 4, 90.0), "needs Mc divisible by 4 with C(Mc/4) = 90");
      first = 0, count = mc / 4 + 1;
      break;
  }
}

const PhotometricSymmetry kSymmetry[] = {PhotometricSymmetry::None, PhotometricSymmetry::Rotational,
                                         PhotometricSymmetry::BilateralC0C180,
                                         PhotometricSymmetry::BilateralC90C270,
                                         PhotometricSymmetry::Quadrant};

void set_opening(double length_mm, double width_mm, double height_mm, PhotometricData& data) {
  data.opening_length_m = length_mm / 1000.0;
  data.opening_width_m = (width_mm > 0.0 ? width_mm : length_mm) / 1000.0;
  data.opening_height_m = height_mm / 1000.0;
  if (length_mm <= 0.0) {
    data.opening_shape = OpeningShape::Point;
    data.opening_length_m = data.opening_width_m = 0.0;
  } else if (width_mm <= 0.0) {  // EULUMDAT: width 0 means circular
    data.opening_shape = height_mm > 0.0 ? OpeningShape::VerticalCylinder : OpeningShape::Disk;
  } else {
    data.opening_shape = height_mm > 0.0 ? OpeningShape::Box : OpeningShape::Rectangle;
  }
}

}  // namespace

PhotometricData parse_ldt(std::string_view text, const std::string& source_name) {
  PhotometricData data;
  data.source_file = source_name;
  data.format = PhotometricFormat::Eulumdat;
  data.format_version = "EULUMDAT";
  const auto lines = photometry_detail::split_lines(text);
  LineReader in(lines, source_name);

  data.keywords.emplace_back("COMPANY", in.text("company identification"));
  in.integer("type indicator Ityp", 0, 3);
  const long isym = in.integer("symmetry indicator Isym", 0, 4);
  const long mc = in.integer("number of C planes Mc", 1, kMaxPlanes);
  in.number("C plane distance Dc");
  const long ng = in.integer("number of gamma angles Ng", 2, kMaxPlanes);
  const int ng_line = in.last_line();
  in.number("gamma distance Dg");
  static const char* const kTextFields[] = {"REPORT", "LUMINAIRE", "LUMCAT", "FILENAME", "DATE"};
  for (const char* key : kTextFields) data.keywords.emplace_back(key, in.text(key));

  for (const char* what : {"luminaire length", "luminaire width", "luminaire height"})
    in.number(what);
  const double area_length = in.number("luminous area length");
  const double area_width = in.number("luminous area width");
  double area_height = 0.0;
  for (const char* what : {"luminous area height C0", "luminous area height C90",
                           "luminous area height C180", "luminous area height C270"})
    area_height = std::max(area_height, in.number(what));
  if (area_length < 0.0 || area_width < 0.0)
    fail(source_name, in.last_line(), "luminous area sizes must be >= 0");
  set_opening(area_length, area_width, area_height, data);

  data.downward_flux_fraction_percent = in.number("downward flux fraction");
  data.light_output_ratio_percent = in.number("light output ratio");
  data.candela_multiplier = in.number("conversion factor for luminous intensities");
  if (!(data.candela_multiplier > 0.0))
    fail(source_name, in.last_line(), "conversion factor for luminous intensities must be > 0");
  in.number("tilt during measurement");

  const LampSets lamps = read_lamp_sets(in);
  data.keywords.emplace_back("LAMP", lamps.types);
  data.absolute_photometry = lamps.absolute;
  data.rated_lumens_lm = lamps.flux_lm;
  data.lamp_count = lamps.lamps;
  data.input_watts = lamps.watts;
  if (!(lamps.flux_lm > 0.0))
    fail(source_name, lamps.flux_line, "lamp flux must be > 0 to turn cd/klm into candela");
  for (int i = 0; i < 10; ++i) in.number("direct ratio");

  const std::vector<double> c = read_angles(in, mc, "C angle", 360.0 - kAngleEps);
  const int c_line = in.last_line();
  const std::vector<double> g = read_angles(in, ng, "gamma angle", 180.0);
  long first = 0, count = 0;
  stored_planes(isym, mc, c, source_name, c_line, first, count);
  if (static_cast<std::size_t>(count) * static_cast<std::size_t>(ng) > kMaxPhotometricValues)
    fail(source_name, ng_line, "intensity table is larger than the accepted 10^6 values");

  photometry_detail::StoredTable table;
  table.type = data.type = PhotometricType::C;
  table.symmetry = data.symmetry = kSymmetry[isym];
  table.vertical_deg = g;
  const double to_cd = lamps.flux_lm / 1000.0 * data.candela_multiplier;
  for (long k = 0; k < count; ++k) {
    const double angle = c[static_cast<std::size_t>((first + k) % mc)];
    table.horizontal_deg.push_back(isym == 3 && angle > 180.0 ? angle - 360.0 : angle);
    for (long j = 0; j < ng; ++j) {
      const double value = in.number("luminous intensity");
      if (value < 0.0) fail(source_name, in.last_line(), "luminous intensities must be >= 0");
      if (!std::isfinite(value * to_cd))
        fail(source_name, in.last_line(), "luminous intensity is too large");
      table.candela.push_back(value * to_cd);
    }
  }
  in.expect_end();
  photometry_detail::unfold(table, data);
  return data;
}

}  // namespace lightsolver
