#pragma once
// Sky luminance models (docs/daylight.md, "Sky"): the 15 CIE standard general skies (ISO
// 15469:2004 / CIE S 011/E:2003), the traditional CIE overcast sky (Moon & Spencer 1942), the
// uniform sky and the Perez all-weather sky (Perez, Seals & Michalsky 1993) with the Perez et al.
// 1990 luminous efficacy models. Pure mathematics: includes nothing of src/.
//
// Every model is one formula, the general sky form
//   raw(Z, chi) = max(0, phi(Z) * f(chi)),
//   phi(Z)  = 1 + a exp(b / cos Z) + m cos Z                 (gradation)
//   f(chi)  = 1 + c (exp(d chi) - k) + e cos^2 chi            (indicatrix)
// with Z the zenith angle of the sky point and chi its angle to the sun, times a scale in cd/m²
// per raw unit. The CIE general skies take k = exp(d pi/2) and m = 0; Moon & Spencer is a = c = e
// = 0, m = 2; the uniform sky a = c = e = m = 0; Perez k = m = 0 with its own a..e. Below the
// horizon the sky is replaced by a uniform ground of luminance rho_g E_h,global / pi.
#include <array>
#include <optional>
#include <string>

namespace lightsolver::daylight {

/// Where b > 0 (a Perez sky outside its fitted conditions) cos Z is floored at this, sin 6°: the
/// lowest row of sky patches at which Radiance's gendaymtx evaluates the model.
inline constexpr double kMinCosZ = 0.10452846326765347;

/// A unit direction, z up (toward the zenith).
struct Direction {
  double x = 0.0, y = 0.0, z = 1.0;
};

/// Parameters of the general sky form (see the file comment).
struct SkyShape {
  double a = 0.0, b = -1.0, m = 0.0;           ///< gradation
  double c = 0.0, d = -1.0, e = 0.0, k = 0.0;  ///< indicatrix
  /// True when the indicatrix depends on the sun (c or e non-zero).
  bool needs_sun() const { return c != 0.0 || e != 0.0; }
  /// raw(Z, chi) for a sky point `toward` (z > 0) and the sun `sun`; clamped at 0.
  double raw(const Direction& toward, const Direction& sun) const;
};

/// The gradation and indicatrix parameters of CIE standard general sky `type` (1..15), from
/// ISO 15469:2004 / CIE S 011/E:2003, Table 1. Throws std::invalid_argument outside 1..15.
SkyShape cie_general_sky(int type);

/// The traditional CIE overcast sky, L = L_z (1 + 2 cos Z) / 3 (Moon & Spencer 1942).
SkyShape cie_overcast_sky();

/// The uniform sky.
SkyShape uniform_sky();

/// Horizontal illuminance of the raw form over the upper hemisphere, ∫ raw(ω) cos Z dω, by
/// composite Gauss-Legendre quadrature in (Z, azimuth about the sun) with the sun's zenith angle
/// and azimuth on panel edges (the indicatrix' kink there). `error` (optional) receives the
/// difference to the same rule on half as many panels, a bound on the error in practice.
double horizontal_integral(const SkyShape& shape, const Direction& sun, double* error = nullptr);

/// The sky models of the `sky` luminaire.
enum class SkyModel { CieGeneral, CieOvercast, Uniform, Perez };

/// How a CIE, overcast or uniform sky's absolute level is given.
enum class SkyNormalisation { ZenithLuminance, DiffuseHorizontalIlluminance };

/// Inputs of the Perez all-weather sky: diffuse horizontal and direct normal, as irradiance
/// (W/m²) or illuminance (lx).
struct PerezInput {
  double diffuse_horizontal = 0.0;
  double direct_normal = 0.0;
  bool illuminance = false;   ///< true: lx; false: W/m²
  int day_of_year = 172;      ///< 1..366, for the extraterrestrial irradiance (eccentricity)
  double dew_point_c = 11.0;  ///< surface dew point: precipitable water for the efficacies
};

/// Everything that defines a sky.
struct SkySpec {
  SkyModel model = SkyModel::CieOvercast;
  int cie_type = 1;              ///< CieGeneral: 1..15
  std::optional<Direction> sun;  ///< toward the sun, unit; needed where the model uses it
  SkyNormalisation normalisation = SkyNormalisation::DiffuseHorizontalIlluminance;
  double level = 10000.0;           ///< cd/m² (zenith luminance) or lx (diffuse horizontal)
  PerezInput perez;                 ///< Perez only
  double ground_reflectance = 0.2;  ///< 0..1: the ground below the horizon
  /// The sun's direct normal illuminance (lx) added to the ground's illuminance (CIE, overcast,
  /// uniform; Perez takes its own from the model). 0: sky only.
  double sun_direct_normal_lx = 0.0;
};

/// What the Perez model made of its inputs.
struct PerezState {
  double epsilon = 1.0;  ///< sky clearness
  double delta = 0.0;    ///< sky brightness
  /// The brightness the luminance coefficients were evaluated at: delta within gendaylit's
  /// range [0.01, 0.6], at least 0.2 for 1.065 < epsilon < 2.8 (gendaylit's check), raised in
  /// steps of 0.01 where the published coefficients give no light above the horizon at all
  /// (the sixth clearness bin, 2.8 <= epsilon < 4.5, at brightness below ~0.05 with the sun
  /// above ~70°).
  double shape_delta = 0.0;
  int bin = 0;  ///< clearness bin, 0..7
  double diffuse_efficacy_lm_w = 0.0;
  double direct_efficacy_lm_w = 0.0;
  double diffuse_horizontal_lx = 0.0;
  double direct_normal_lx = 0.0;
};

/// A sky with its absolute level: luminance in every direction.
class Sky {
 public:
  /// Builds the sky. Throws std::invalid_argument naming the offending input (`sun`, `level`,
  /// `cie_type`, `ground_reflectance`, `perez.*`).
  explicit Sky(const SkySpec& spec);

  /// Luminance (cd/m²) seen looking toward `toward` (unit): the sky above the horizon (z > 0),
  /// the ground's below.
  double luminance(const Direction& toward) const;
  /// The sky's luminance toward the zenith (cd/m²).
  double zenith_luminance() const { return scale_ * shape_.raw({0, 0, 1}, sun_); }
  /// Diffuse horizontal illuminance of the unobstructed sky (lx).
  double diffuse_horizontal_lx() const { return scale_ * raw_horizontal_; }
  /// Uniform ground luminance below the horizon (cd/m²).
  double ground_luminance() const { return ground_luminance_; }
  /// Relative error bound of diffuse_horizontal_lx() from the quadrature.
  double quadrature_error() const { return quadrature_error_; }
  /// cd/m² per raw unit, and the form and sun the luminance is made of.
  double scale() const { return scale_; }
  const SkyShape& shape() const { return shape_; }
  const Direction& sun() const { return sun_; }
  /// The Perez model's state (Perez only).
  const std::optional<PerezState>& perez() const { return perez_; }

 private:
  SkyShape shape_;
  Direction sun_;
  double scale_ = 0.0;
  double raw_horizontal_ = 0.0;
  double quadrature_error_ = 0.0;
  double ground_luminance_ = 0.0;
  std::optional<PerezState> perez_;
};

/// Perez et al. 1990 / Perez, Seals & Michalsky 1993 for a sun at zenith angle `sun_zenith_rad`:
/// clearness, brightness, bin, luminous efficacies and illuminances from `in`. Illuminance
/// inputs are turned into irradiance by the efficacy models (fixed point, as Radiance's
/// gendaymtx does). Throws std::invalid_argument for negative or non-finite inputs.
PerezState perez_state(const PerezInput& in, double sun_zenith_rad);

/// The Perez 1993 sky form: a..e of the clearness bin at brightness `shape_delta` and the sun's
/// zenith angle.
SkyShape perez_shape(const PerezState& state, double sun_zenith_rad);

}  // namespace lightsolver::daylight
