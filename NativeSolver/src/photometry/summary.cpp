// Text summary of a distribution: lumens, peak, beam and field angles.

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <sstream>

#include "photometry_internal.hpp"

namespace lightsolver {

namespace photometry_detail {

// Intensity profile along the great circle through the aim (-z) and `side` (+x or +y):
// direction(a) = sin(a) side + cos(a) (-z), a in [-180, 180] degrees, 0.1 degree steps.
std::vector<double> great_circle_profile(const SamplerTables& t, const glm::dvec3& side,
                                         std::vector<double>& angles_deg) {
  std::vector<double> profile;
  angles_deg.clear();
  for (int k = -1800; k <= 1800; ++k) {
    const double a = k * 0.1, r = a * std::numbers::pi / 180.0;
    angles_deg.push_back(a);
    profile.push_back(eval_direction(t, std::sin(r) * side + std::cos(r) * glm::dvec3(0, 0, -1)));
  }
  return profile;
}

// Full angle between the points either side of the profile's peak where the intensity falls
// to `fraction` of it (linear between samples); NaN if it never falls that low.
double spread_angle_deg(const std::vector<double>& profile, const std::vector<double>& angles,
                        double fraction) {
  std::size_t peak = 0;
  for (std::size_t k = 1; k < profile.size(); ++k)
    if (profile[k] > profile[peak]) peak = k;
  const double level = fraction * profile[peak];
  if (!(profile[peak] > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  const auto crossing = [&](std::size_t inside, std::size_t outside) {
    const double f = (profile[inside] - level) / (profile[inside] - profile[outside]);
    return angles[inside] + f * (angles[outside] - angles[inside]);
  };
  std::size_t lo = peak, hi = peak;
  while (lo > 0 && profile[lo - 1] >= level) --lo;
  while (hi + 1 < profile.size() && profile[hi + 1] >= level) ++hi;
  if (lo == 0 || hi + 1 == profile.size()) return std::numeric_limits<double>::quiet_NaN();
  return crossing(hi, hi + 1) - crossing(lo, lo - 1);
}

}  // namespace photometry_detail

namespace {

std::string fixed(double v, int digits) {
  if (!std::isfinite(v)) return "n/a";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

std::string keyword(const PhotometricData& d, const char* key) {
  for (const auto& [k, v] : d.keywords)
    if (k == key && !v.empty()) return v.substr(0, v.find('\n'));
  return "";
}

void describe_file(std::ostringstream& out, const PhotometricData& d) {
  out << "File: " << d.source_file << "\n";
  out << "Format: " << (d.format == PhotometricFormat::Ies ? "IES " : "") << d.format_version
      << "\n";
  for (const char* key : {"MANUFAC", "COMPANY", "LUMINAIRE", "LUMCAT", "LAMP", "TEST"}) {
    const std::string v = keyword(d, key);
    if (!v.empty()) out << "[" << key << "] " << v << "\n";
  }
  out << "Photometric type: " << to_string(d.type) << ", symmetry: " << to_string(d.symmetry)
      << "\n";
  out << "Grid (unfolded): " << d.horizontal_angles_deg.size() << " horizontal x "
      << d.vertical_angles_deg.size() << " vertical angles\n";
}

void describe_lumens(std::ostringstream& out, const PhotometricData& d, const PhotometryFacts& f) {
  if (d.absolute_photometry) {
    out << "Lumens (file): absolute photometry";
    if (d.rated_lumens_lm > 0) out << ", luminaire " << fixed(d.rated_lumens_lm, 1) << " lm";
    out << "\n";
  } else {
    out << "Lumens (file): " << fixed(d.rated_lumens_lm, 1) << " lm lamp lumens (" << d.lamp_count
        << " lamp" << (d.lamp_count == 1 ? "" : "s") << ")\n";
  }
  out << "Lumens (integrated): " << fixed(f.integrated_lumens_lm, 1) << " lm";
  if (d.rated_lumens_lm > 0)
    out << " (" << fixed(100.0 * f.integrated_lumens_lm / d.rated_lumens_lm, 1)
        << " % of the file's)";
  out << "\n";
  if (d.light_output_ratio_percent > 0)
    out << "Light output ratio (file): " << fixed(d.light_output_ratio_percent, 1) << " %\n";
}

void describe_peak(std::ostringstream& out, const PhotometricData& d, const PhotometryFacts& f) {
  if (d.candela.empty()) return;
  const bool c = d.type == PhotometricType::C;
  out << "Peak: " << fixed(f.peak_cd, 1) << " cd at " << (c ? "C " : "H ")
      << fixed(f.peak_horizontal_deg, 1) << ", " << (c ? "gamma " : "V ")
      << fixed(f.peak_vertical_deg, 1) << " deg\n";
}

void describe_spreads(std::ostringstream& out, const PhotometricData& d, const PhotometryFacts& f) {
  const bool c = d.type == PhotometricType::C;
  const char* names[2] = {c ? "C0-C180" : "H = 0", c ? "C90-C270" : "V = 0"};
  out << "Beam angle (50 %):";
  for (int k = 0; k < 2; ++k)
    out << (k ? ", " : " ") << names[k] << " " << fixed(f.beam_angle_deg[k], 1) << " deg";
  out << "\nField angle (10 %):";
  for (int k = 0; k < 2; ++k)
    out << (k ? ", " : " ") << names[k] << " " << fixed(f.field_angle_deg[k], 1) << " deg";
  out << "\n";
}

}  // namespace

PhotometryFacts photometry_facts(const PhotometricData& d) {
  PhotometryFacts f;
  f.rated_lumens_lm = d.rated_lumens_lm;
  f.absolute_photometry = d.absolute_photometry;
  f.lamp_count = d.lamp_count;
  const SamplerTables t = photometry_detail::make_tables(d);
  f.integrated_lumens_lm = t.cell_cdf.empty() ? 0.0 : t.cell_cdf.back();
  std::size_t best = 0;
  for (std::size_t k = 1; k < d.candela.size(); ++k)
    if (d.candela[k] > d.candela[best]) best = k;
  if (!d.candela.empty()) {
    const std::size_t nv = d.vertical_angles_deg.size();
    f.peak_cd = d.candela[best];
    f.peak_horizontal_deg = d.horizontal_angles_deg[best / nv];
    f.peak_vertical_deg = d.vertical_angles_deg[best % nv];
  }
  const glm::dvec3 sides[2] = {{1, 0, 0}, {0, 1, 0}};
  for (int k = 0; k < 2; ++k) {
    std::vector<double> angles;
    const auto profile = photometry_detail::great_circle_profile(t, sides[k], angles);
    f.beam_angle_deg[k] = photometry_detail::spread_angle_deg(profile, angles, 0.5);
    f.field_angle_deg[k] = photometry_detail::spread_angle_deg(profile, angles, 0.1);
  }
  return f;
}

std::string photometry_summary(const PhotometricData& d) {
  std::ostringstream out;
  describe_file(out, d);
  const PhotometryFacts f = photometry_facts(d);
  describe_lumens(out, d, f);
  describe_peak(out, d, f);
  describe_spreads(out, d, f);
  out << "Opening: " << to_string(d.opening_shape) << " " << fixed(d.opening_length_m, 3) << " x "
      << fixed(d.opening_width_m, 3) << " x " << fixed(d.opening_height_m, 3)
      << " m (length along C0 x width x height)\n";
  out << "Tilt: " << d.tilt;
  if (!d.tilt_data.factors.empty()) {
    out << " (lamp geometry " << d.tilt_data.lamp_geometry << "; factor at tilt:";
    for (std::size_t i = 0; i < d.tilt_data.factors.size(); ++i) {
      out << " " << d.tilt_data.angles_deg[i] << "°=" << d.tilt_data.factors[i];
    }
    out << (d.type == PhotometricType::C ? "; applied at the aim's angle from straight down)"
                                         : "; not applied to type A/B photometry)");
  }
  out << "\n";
  for (const auto& w : d.warnings) out << "Warning: " << w << "\n";
  return out.str();
}

}  // namespace lightsolver
