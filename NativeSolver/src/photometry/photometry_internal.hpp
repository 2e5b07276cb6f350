#pragma once
// Internal helpers shared by the photometry sources (not installed, not public API).

#include <cstddef>
#include <glm/vec3.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "lightsolver/photometry.hpp"

namespace lightsolver::photometry_detail {

/// Angles closer than this (degrees) are one angle: the IES and LDT readers' tolerance.
inline constexpr double kAngleEps = 1e-6;

/// One line of a text file, without its terminator, with its 1-based number.
struct Line {
  std::string_view text;
  int number = 0;
};

/// Splits on \n, \r\n or \r; drops a UTF-8 byte-order mark and a trailing Ctrl-Z (DOS EOF).
std::vector<Line> split_lines(std::string_view text);

/// Strips spaces, tabs and other ASCII whitespace at both ends.
std::string_view trim(std::string_view s);

/// Throws InputError(file, "line N", what).
[[noreturn]] void fail(const std::string& file, int line, const std::string& what);

/// A token shown in a message: at most 32 characters, non-printable bytes escaped.
std::string quote(std::string_view token);

/// A number for messages ("%.10g": no huge fixed-point strings, no conversions that overflow).
std::string format_number(double value);

/// Parses a whole token as a finite decimal number ('+' allowed; a ',' decimal separator when
/// `comma_decimal`). Returns false if the token is not a number; NaN and infinities count as
/// not-a-number too.
bool parse_number(std::string_view token, double& out, bool comma_decimal = false);

/// Reads numbers from consecutive lines, separated by whitespace and/or commas (LM-63 allows
/// both). Every error names the line.
class TokenStream {
 public:
  TokenStream(const std::vector<Line>& lines, std::size_t first_line, std::string file);

  /// Next number; `what` names it in messages ("number of vertical angles").
  double number(const std::string& what);
  /// Next number that must be an integer in [lo, hi] (LM-63-1986 writes counts as "3.0").
  long integer(const std::string& what, long lo, long hi);
  /// True when only whitespace (and separators) is left.
  bool at_end();
  /// Line of the next token, or of the last line at the end.
  int line();
  /// Line of the token read last.
  int last_line() const { return last_line_; }
  const std::string& file() const { return file_; }

 private:
  bool skip_separators();  // false at the end of the text
  const std::vector<Line>& lines_;
  std::size_t line_index_;
  std::size_t pos_ = 0;
  std::string file_;
  int last_line_ = 0;
};

/// The file's table as stored (absolute candela), before symmetry unfolding.
struct StoredTable {
  PhotometricType type = PhotometricType::C;
  PhotometricSymmetry symmetry = PhotometricSymmetry::None;
  std::vector<double> horizontal_deg;  ///< stored planes, strictly increasing
  std::vector<double> vertical_deg;
  std::vector<double> candela;  ///< [h * nv + v]
};

/// Fills data.horizontal_angles_deg / vertical_angles_deg / candela with the full table
/// (type C: 0..360; types A, B: mirrored about H = 0 when laterally symmetric).
void unfold(const StoredTable& table, PhotometricData& data);

/// Builds the (plane, polar) grid, cell CDF and rejection bounds of a distribution.
SamplerTables make_tables(const PhotometricData& data);

/// Bilinear intensity at plane angle p and polar angle t (degrees); zero outside the grid.
double eval_angles(const SamplerTables& t, double plane_deg, double polar_deg);

/// Intensity toward a direction (need not be normalised) in the luminaire frame.
double eval_direction(const SamplerTables& t, const glm::dvec3& d);

/// Unit direction of (plane, polar) angles in degrees.
glm::dvec3 direction_of(const SamplerTables& t, double plane_deg, double polar_deg);

/// Intensity along the great circle through the aim (-z) and `side` (+x or +y):
/// direction(a) = sin(a) side + cos(a) (-z) for a = -180..180 degrees in 0.1 degree steps.
std::vector<double> great_circle_profile(const SamplerTables& t, const glm::dvec3& side,
                                         std::vector<double>& angles_deg);

/// Full angle between the two points either side of the profile's peak where the intensity
/// falls to `fraction` of the peak; NaN when it never does.
double spread_angle_deg(const std::vector<double>& profile, const std::vector<double>& angles,
                        double fraction);

/// Reads a whole file (at most 64 MiB); throws InputError when it cannot.
std::string read_file(const std::string& path);

}  // namespace lightsolver::photometry_detail
