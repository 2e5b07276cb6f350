// Text scanning shared by the IES and EULUMDAT parsers, file loading and enum names.

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "photometry_internal.hpp"

namespace lightsolver::photometry_detail {

namespace {
constexpr std::uintmax_t kMaxFileBytes = 64u << 20;  // a 10^6-value table is ~10 MB

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\v' || c == '\f'; }
}  // namespace

std::vector<Line> split_lines(std::string_view text) {
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  while (!text.empty() && text.back() == '\x1A') text.remove_suffix(1);
  std::vector<Line> lines;
  std::size_t start = 0;
  int number = 1;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '\n' && text[i] != '\r') continue;
    lines.push_back({text.substr(start, i - start), number++});
    if (text[i] == '\r' && i + 1 < text.size() && text[i + 1] == '\n') ++i;
    start = i + 1;
  }
  if (start < text.size()) lines.push_back({text.substr(start), number});
  return lines;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

void fail(const std::string& file, int line, const std::string& what) {
  throw InputError(file, line > 0 ? "line " + std::to_string(line) : std::string(), what);
}

std::string quote(std::string_view token) {
  std::string out = "'";
  for (std::size_t i = 0; i < token.size() && i < 32; ++i) {
    const unsigned char c = static_cast<unsigned char>(token[i]);
    if (c >= 0x20 && c < 0x7F) {
      out += static_cast<char>(c);
    } else {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02X", c);
      out += buf;
    }
  }
  if (token.size() > 32) out += "...";
  return out + "'";
}

bool parse_number(std::string_view token, double& out, bool comma_decimal) {
  std::string local;
  if (comma_decimal && token.find(',') != std::string_view::npos) {
    local.assign(token);
    std::replace(local.begin(), local.end(), ',', '.');
    token = local;
  }
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty() || token.front() == '+') return false;
  // from_chars also accepts "nan" and "inf": we do not, and insist on a digit somewhere.
  if (std::none_of(token.begin(), token.end(), [](char c) { return c >= '0' && c <= '9'; }))
    return false;
  double value = 0.0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || end != token.data() + token.size() || !std::isfinite(value))
    return false;
  out = value;
  return true;
}

TokenStream::TokenStream(const std::vector<Line>& lines, std::size_t first_line, std::string file)
    : lines_(lines), line_index_(first_line), file_(std::move(file)) {}

bool TokenStream::skip_separators() {
  while (line_index_ < lines_.size()) {
    const std::string_view text = lines_[line_index_].text;
    while (pos_ < text.size() && (is_space(text[pos_]) || text[pos_] == ',')) ++pos_;
    if (pos_ < text.size()) return true;
    ++line_index_;
    pos_ = 0;
  }
  return false;
}

bool TokenStream::at_end() { return !skip_separators(); }

int TokenStream::line() {
  if (skip_separators()) return lines_[line_index_].number;
  return lines_.empty() ? 0 : lines_.back().number;
}

double TokenStream::number(const std::string& what) {
  if (!skip_separators())
    fail(file_, line(), "file ends where the " + what + " should be (truncated data?)");
  const std::string_view text = lines_[line_index_].text;
  std::size_t end = pos_;
  while (end < text.size() && !is_space(text[end]) && text[end] != ',') ++end;
  const std::string_view token = text.substr(pos_, end - pos_);
  last_line_ = lines_[line_index_].number;
  pos_ = end;
  double value = 0.0;
  if (!parse_number(token, value))
    fail(file_, last_line_, what + ": " + quote(token) + " is not a finite number");
  return value;
}

std::string format_number(double value) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", value);
  return buf;
}

long TokenStream::integer(const std::string& what, long lo, long hi) {
  const double value = number(what);
  if (value != std::floor(value))
    fail(file_, last_line_, what + " must be a whole number (got " + format_number(value) + ")");
  if (value < static_cast<double>(lo) || value > static_cast<double>(hi))
    fail(file_, last_line_,
         what + " must be between " + std::to_string(lo) + " and " + std::to_string(hi) + " (got " +
             format_number(value) + ")");
  return static_cast<long>(value);  // in [lo, hi]: exact
}

std::string read_file(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path, "", "cannot open file");
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw InputError(path, "", "cannot read file size");
  if (size > kMaxFileBytes)
    throw InputError(path, "", "file is larger than 64 MiB: refused (not a photometric file?)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "cannot open file");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

}  // namespace lightsolver::photometry_detail

namespace lightsolver {

namespace {
std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

// Unknown extension: IES files have a TILT= line near the top, EULUMDAT files never do.
bool looks_like_ies(std::string_view text) {
  return text.substr(0, 4096).find("TILT") != std::string_view::npos;
}
}  // namespace

PhotometricData load_photometry(const std::string& path) {
  const std::string text = photometry_detail::read_file(path);
  const std::string ext = lower_extension(path);
  const bool ies = ext == ".ies" || (ext != ".ldt" && looks_like_ies(text));
  if (ies) {
    const std::string dir = std::filesystem::path(path).parent_path().string();
    return parse_ies(text, path, dir.empty() ? std::string(".") : dir);
  }
  return parse_ldt(text, path);
}

const char* to_string(PhotometricType type) {
  switch (type) {
    case PhotometricType::C:
      return "C";
    case PhotometricType::B:
      return "B";
    case PhotometricType::A:
      return "A";
  }
  return "?";
}

const char* to_string(PhotometricSymmetry symmetry) {
  switch (symmetry) {
    case PhotometricSymmetry::None:
      return "none";
    case PhotometricSymmetry::Rotational:
      return "rotational";
    case PhotometricSymmetry::BilateralC0C180:
      return "bilateral about C0-C180";
    case PhotometricSymmetry::BilateralC90C270:
      return "bilateral about C90-C270";
    case PhotometricSymmetry::Quadrant:
      return "quadrant (C0-C180 and C90-C270)";
    case PhotometricSymmetry::LateralAB:
      return "lateral about H = 0";
  }
  return "?";
}

const char* to_string(OpeningShape shape) {
  switch (shape) {
    case OpeningShape::Point:
      return "point";
    case OpeningShape::Rectangle:
      return "rectangle";
    case OpeningShape::Box:
      return "box";
    case OpeningShape::Disk:
      return "disk/ellipse";
    case OpeningShape::VerticalCylinder:
      return "vertical cylinder";
    case OpeningShape::Sphere:
      return "sphere/ellipsoid";
    case OpeningShape::HorizontalCylinderC0:
      return "horizontal cylinder along C0";
    case OpeningShape::HorizontalCylinderC90:
      return "horizontal cylinder along C90";
    case OpeningShape::VerticalDisk:
      return "vertical disk facing C0";
  }
  return "?";
}

}  // namespace lightsolver
