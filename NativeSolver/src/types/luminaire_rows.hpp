#pragma once
// What the luminaire types' rows share across their files (luminaire_types.cpp holds the table
// and the point, spot, area and directional rows; luminaire_photometric.cpp the photometric row).
#include <cstdint>
#include <glm/vec3.hpp>
#include <optional>
#include <string>
#include <vector>

#include "shared/luminaires.h"
#include "types/luminaire_types.hpp"

namespace lightsolver::detail {

class JsonNode;

namespace luminaire_rows {

/// Numbers in messages: 6 significant digits, as the validator prints them.
std::string show(double v);
/// Where a luminaire with a position is, and moving it there.
glm::dvec3 at_position(const Luminaire& l);
void move_position(Luminaire& l, const glm::dvec3& c);
/// The photometric aim, for an aim design variable.
glm::dvec3* file_aim(Luminaire& l);
/// Emission from the prepared luminaire's position within `half_angle_rad` of its axis.
EmissionSupport from_point(const PreparedLuminaire& l, double half_angle_rad);
/// Not a glare source, because `why_not`.
GlareShape no_glare(std::string why_not);
/// Checks `key` as a direction and makes it unit length.
void unit_direction(const LuminaireChecks& c, const char* key, glm::dvec3& v);
/// A beam's (directional, sun) `illuminance_lx`: finite, >= 0, at most 10^7 lx.
void check_beam_illuminance(const LuminaireChecks& c, const Luminaire& l);
/// A beam's derived `flux_lm` (illuminance x the opening's area across it): at most 10^12 lm.
void check_beam_flux(const LuminaireChecks& c, const Luminaire& l);

/// The emit hook of a type whose emission both backends run from one text: an LS_EMISSION of
/// Shaders/shared/luminaires.h, e.g. `shared_emission<shared::emit_point>`.
template <void (*Emission)(const PreparedLuminaire&, vec3&, vec3&, PathRng&)>
EmittedRay shared_emission(const PreparedLuminaire& l, PathRng& rng) {
  EmittedRay ray;
  Emission(l, ray.origin, ray.direction, rng);
  return ray;
}

}  // namespace luminaire_rows

/// The row of luminaire_photometric.cpp.
LuminaireType photometric_luminaire_type();
/// The row of luminaire_sun.cpp.
LuminaireType sun_luminaire_type();
/// The row of luminaire_sky.cpp.
LuminaireType sky_luminaire_type();
/// A sky's (or a sun's) `portals` array (luminaire_sky.cpp).
std::vector<SkyDefinition::Portal> read_portals(const JsonNode& n);
/// A daylight opening's `glazing` object (luminaire_sky.cpp; the sky's portals, the sun).
GlazingDefinition read_glazing(const JsonNode& n);
/// Checks it (errors name `<at>.transmittance` ...) and returns the factor on the opening's light
/// for an opening whose normal makes cos θ = `cos_i` with the beam (the sun's τ(θ) x frame x
/// maintenance).
double glazing_factor(const LuminaireChecks& c, const std::string& at, const GlazingDefinition& g,
                      double cos_i);
/// The factor a checked glazing puts on a beam at cos θ = `cos_i` to its opening's normal:
/// τ(θ) × frame × maintenance (luminaire_sun.cpp; the sun's flux and the direct sun at points,
/// src/embree/direct_sun.cpp); 1 without glazing (an open hole).
double beam_glazing(const std::optional<GlazingDefinition>& g, double cos_i);
/// The sun's disc (0.53°) through an opening whose normal (into the room) makes n·d = `t` with
/// the beam: (1 / (π sin²α)) ∫_disc max(0, n·ω) dω, so that the flux is E · area · share; t for
/// the disc wholly in front, 0 wholly behind, the exact cut cap in between (docs/daylight.md).
double sun_disc_share(double t);
/// A sun's GPU record (Shaders/emit.glsl, emit_sun_gpu): through portals, appended to `floats`
/// (thresholds to `thresholds`) and its offset returned; through its own opening, 0xFFFFFFFF.
std::uint32_t pack_sun_record(const PreparedLuminaire& l, std::vector<float>& floats,
                              std::vector<std::uint64_t>& thresholds,
                              std::uint64_t (*threshold)(double c, double total));
/// A sky luminaire's GPU record (Shaders/sky.glsl's layout) appended to `floats`, its cell and
/// portal thresholds to `thresholds` (`threshold(c, total)`: the 53-bit threshold of cumulative
/// `c` out of `total`, vulkan/gpu_scene.cpp's); returns the record's offset in `floats`.
std::uint32_t pack_sky_record(const PreparedLuminaire& l, std::vector<float>& floats,
                              std::vector<std::uint64_t>& thresholds,
                              std::uint64_t (*threshold)(double c, double total));

}  // namespace lightsolver::detail
