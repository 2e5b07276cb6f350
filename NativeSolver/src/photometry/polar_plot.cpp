// Polar intensity diagram as a PNG: the curves are drawn here, stb_image_write encodes them.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <string>

#include "lightsolver/output_file.hpp"
#include "photometry_internal.hpp"

// Static implementation: private to this file, so it cannot clash with another user of stb.
#define STB_IMAGE_WRITE_STATIC
#define STBI_WRITE_NO_STDIO  // encoded in memory, written by write_file_atomically
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

namespace lightsolver {

namespace {

constexpr int kSize = 640;    // image width and height (pixels)
constexpr int kRadius = 270;  // radius of the 100 % circle
constexpr int kCentre = kSize / 2;

struct Rgb {
  std::uint8_t r, g, b;
};
constexpr Rgb kGrid{200, 200, 200}, kText{40, 40, 40};
constexpr Rgb kFirst{200, 30, 30}, kSecond{30, 70, 200};

class Canvas {
 public:
  Canvas() : pixels_(static_cast<std::size_t>(kSize) * kSize * 3, 255) {}

  void set(int x, int y, Rgb c) {
    if (x < 0 || y < 0 || x >= kSize || y >= kSize) return;
    std::uint8_t* p = &pixels_[(static_cast<std::size_t>(y) * kSize + x) * 3];
    p[0] = c.r, p[1] = c.g, p[2] = c.b;
  }

  // Dots along the segment, `width` pixels thick: plenty for a diagram, no dependencies.
  void line(double x0, double y0, double x1, double y1, Rgb c, int width) {
    if (!std::isfinite(x0 + y0 + x1 + y1)) return;
    const double length = std::min(std::hypot(x1 - x0, y1 - y0), 4.0 * kSize);
    const int steps = static_cast<int>(std::ceil(length)) + 1;
    for (int k = 0; k <= steps; ++k) {
      const double f = static_cast<double>(k) / steps;
      dot(x0 + f * (x1 - x0), y0 + f * (y1 - y0), c, width);
    }
  }

  void circle(double radius, Rgb c) {
    const int steps = static_cast<int>(2 * std::numbers::pi * radius) + 8;
    for (int k = 0; k < steps; ++k) {
      const double a = 2 * std::numbers::pi * k / steps;
      dot(kCentre + radius * std::cos(a), kCentre + radius * std::sin(a), c, 1);
    }
  }

  void text(int x, int y, const std::string& s, Rgb c);

  const std::uint8_t* data() const { return pixels_.data(); }

 private:
  void dot(double x, double y, Rgb c, int width) {
    const int r = width / 2;
    for (int dy = -r; dy <= r; ++dy)
      for (int dx = -r; dx <= r; ++dx)
        set(static_cast<int>(std::lround(x)) + dx, static_cast<int>(std::lround(y)) + dy, c);
  }
  std::vector<std::uint8_t> pixels_;
};

// 5 x 7 glyphs, one byte per row, bit 4 = leftmost column.
struct Glyph {
  char c;
  std::uint8_t rows[7];
};
constexpr Glyph kFont[] = {
    {'0', {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}},
    {'1', {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E}},
    {'2', {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}},
    {'3', {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E}},
    {'4', {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}},
    {'5', {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E}},
    {'6', {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}},
    {'7', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}},
    {'8', {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}},
    {'9', {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C}},
    {'A', {0x0E, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11}},
    {'C', {0x0E, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0E}},
    {'D', {0x1E, 0x11, 0x11, 0x11, 0x11, 0x11, 0x1E}},
    {'H', {0x11, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11}},
    {'M', {0x11, 0x1B, 0x15, 0x15, 0x11, 0x11, 0x11}},
    {'V', {0x11, 0x11, 0x11, 0x11, 0x11, 0x0A, 0x04}},
    {'X', {0x11, 0x11, 0x0A, 0x04, 0x0A, 0x11, 0x11}},
    {'=', {0x00, 0x00, 0x1F, 0x00, 0x1F, 0x00, 0x00}},
    {'-', {0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00}},
    {'.', {0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C}},
};

void Canvas::text(int x, int y, const std::string& s, Rgb c) {
  constexpr int kScale = 2;
  for (char ch : s) {
    for (const Glyph& g : kFont) {
      if (g.c != ch) continue;
      for (int row = 0; row < 7; ++row)
        for (int col = 0; col < 5; ++col)
          if (g.rows[row] & (0x10 >> col))
            for (int k = 0; k < kScale * kScale; ++k)
              set(x + col * kScale + k % kScale, y + row * kScale + k / kScale, c);
    }
    x += 6 * kScale;  // unknown characters (and spaces) leave a gap
  }
}

void draw_grid(Canvas& canvas) {
  for (int k = 1; k <= 4; ++k) canvas.circle(kRadius * k / 4.0, kGrid);
  for (int deg = 0; deg < 360; deg += 30) {
    const double a = deg * std::numbers::pi / 180.0;
    canvas.line(kCentre, kCentre, kCentre + kRadius * std::sin(a), kCentre + kRadius * std::cos(a),
                kGrid, 1);
  }
}

// Angle a from the aim (drawn downward), positive toward the +side, to the right.
void draw_curve(Canvas& canvas, const std::vector<double>& profile,
                const std::vector<double>& angles, double peak, Rgb colour) {
  for (std::size_t k = 1; k < profile.size(); ++k) {
    const auto point = [&](std::size_t i, double& x, double& y) {
      const double r = kRadius * profile[i] / peak, a = angles[i] * std::numbers::pi / 180.0;
      x = kCentre + r * std::sin(a);
      y = kCentre + r * std::cos(a);
    };
    double x0, y0, x1, y1;
    point(k - 1, x0, y0);
    point(k, x1, y1);
    canvas.line(x0, y0, x1, y1, colour, 3);
  }
}

}  // namespace

void write_polar_plot_png(const PhotometricData& data, const std::string& path) {
  const SamplerTables t = photometry_detail::make_tables(data);
  std::vector<double> angles;
  const auto first = photometry_detail::great_circle_profile(t, {1, 0, 0}, angles);
  const auto second = photometry_detail::great_circle_profile(t, {0, 1, 0}, angles);
  const double peak = std::max(*std::max_element(first.begin(), first.end()),
                               *std::max_element(second.begin(), second.end()));
  Canvas canvas;
  draw_grid(canvas);
  if (peak > 0.0 && std::isfinite(peak)) {
    draw_curve(canvas, first, angles, peak, kFirst);
    draw_curve(canvas, second, angles, peak, kSecond);
  }
  const bool c = data.type == PhotometricType::C;
  canvas.text(12, 12, c ? "C0-C180" : "H=0", kFirst);
  canvas.text(12, 34, c ? "C90-C270" : "V=0", kSecond);
  char label[64];
  std::snprintf(label, sizeof label, "MAX %.0f CD", peak);
  canvas.text(12, kSize - 26, label, kText);
  // Encoded in memory, then written atomically: a failed write never leaves half a PNG.
  std::string png;
  const auto append = [](void* context, void* bytes, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(bytes), std::size_t(size));
  };
  if (!stbi_write_png_to_func(append, &png, kSize, kSize, 3, canvas.data(), kSize * 3))
    throw std::runtime_error(path + ": cannot encode the PNG image");
  write_file_atomically(path, png);
}

}  // namespace lightsolver
