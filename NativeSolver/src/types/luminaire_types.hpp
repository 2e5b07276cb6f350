#pragma once
// One row per luminaire type: how the scene file spells it, how it is read, checked, prepared
// and emitted on the CPU, the flux it emits, where and in which directions it emits (target
// reach), what it is as a glare source and the effect it adds. The reader (scene_json.cpp),
// the validator (scene.cpp), prepare() (prepared_scene.cpp), the CPU emitter (emitters.hpp),
// the reach check (target_reach.cpp), the effects (scene_effects.cpp) and the glare terms
// (glare/glare_terms.cpp) look the type up here instead of switching over Luminaire::Type.
// The GPU's side of a type is its entry in Shaders/shared/luminaires.h (code, switch, emission;
// the point, area and directional emissions there are also these rows' emit): docs/solver.md,
// "Adding a luminaire type".
#include <cstddef>
#include <glm/vec3.hpp>
#include <numbers>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "lightsolver/scene.hpp"
#include "model/prepared_scene.hpp"

namespace lightsolver::detail {

class JsonNode;

/// What a type's check may ask of the scene validator. `key` names a field of the luminaire
/// being checked (the validator turns it into "luminaires[i].key"); failures throw InputError.
class LuminaireChecks {
 public:
  virtual ~LuminaireChecks() = default;
  [[noreturn]] virtual void fail(const char* key, const std::string& what) const = 0;
  /// Finite and within 10^9 m of the origin.
  virtual void coordinates(const char* key, const glm::dvec3& v) const = 0;
  /// Finite, non-zero and normalisable (the caller normalises).
  virtual void direction(const char* key, const glm::dvec3& v) const = 0;
  /// corner, edge1, edge2: finite, non-zero, not parallel (`what` ends the parallel message).
  virtual void parallelogram(const Luminaire& l, const char* what) const = 0;
  /// flux_lm finite, >= 0 and, with the TILT factor, at most 10^12 lm. `note` follows the
  /// value in the message (e.g. where the number came from).
  virtual void flux(const Luminaire& l, const char* note) const = 0;
};

/// Where a luminaire emits from (within `radius` of the convex hull of `points`, local
/// coordinates) and in which directions (within `half_angle_rad` of `axis`; pi: every one).
/// target_reach.cpp proves from it that a target faces away from every luminaire.
struct EmissionSupport {
  std::vector<glm::dvec3> points;
  double radius = 0.0;
  glm::dvec3 axis{0.0, 0.0, 1.0};
  double half_angle_rad = std::numbers::pi;
};

/// A luminaire as a discomfort-glare source (CIE 117), for glare/glare_terms.cpp, which rates
/// it: a Lambertian luminous area, a photometric file's luminous body, or none and why. Only
/// geometry and photometry here: the rating is the glare layer's.
struct GlareShape {
  enum class Kind { None, LambertianArea, PhotometricBody };
  Kind kind = Kind::None;
  std::string why_not;     ///< None: why it is no glare source (results' why_not)
  glm::dvec3 centre{0.0};  ///< where the eye sees it (world)
  glm::dvec3 normal{0.0};  ///< LambertianArea: its emitting side, of length area_m2
  double area_m2 = 0.0;    ///< LambertianArea
  double flux_lm = 0.0;    ///< LambertianArea: the flux it emits
  glm::dvec3 aim{0.0, 0.0, -1.0}, c0{1.0, 0.0, 0.0};  ///< PhotometricBody: the file's frame
  double candela_scale = 0.0;  ///< PhotometricBody: file candela -> traced intensity (TILT too)
};

/// One sample of a luminaire's direct light at a receiver point (next-event estimation,
/// estimate/next_event.cpp): the point a shadow ray must reach unblocked (local coordinates) and
/// the illuminance it then gives on a surface facing it (lx, perpendicular to `to - x`; the
/// caller applies the receiver's cosine). Its expectation over the sample's random numbers is
/// the luminaire's direct illuminance as its photons deliver it. lux = 0: no ray needed.
struct LightSample {
  glm::dvec3 to{0.0};
  double lux = 0.0;
};

/// One luminaire type. Every hook is required, except `direct`.
struct LuminaireType {
  Luminaire::Type type;
  const char* name;  ///< "type" in the scene file
  /// The keys of its scene-file entry (besides power_w and group, which every type has).
  std::span<const char* const> keys;
  /// Reads the type's keys (rejecting unknown ones); "name" and "type" are already read.
  /// `base_dir`: the scene file's folder, for files the luminaire refers to.
  void (*read)(const JsonNode& n, Luminaire& l, const std::string& base_dir);
  /// Checks value ranges and normalises directions, in the order the messages should come.
  void (*check)(const LuminaireChecks& c, Luminaire& l);
  /// Fills the type's part of `p` (position, corner and edges are already set).
  void (*prepare)(const Luminaire& l, PreparedLuminaire& p);
  /// Draws one photon's start and direction (local coordinates) from the prepared luminaire;
  /// prepare() stores it in PreparedLuminaire::emit.
  EmittedRay (*emit)(const PreparedLuminaire& l, PathRng& rng);
  /// The flux it emits as traced (lm): flux_lm, times a photometric file's TILT factor.
  double (*emitted_flux)(const Luminaire& l);
  /// Where and in which directions the prepared luminaire can emit (target_reach.cpp).
  EmissionSupport (*support)(const PreparedLuminaire& l);
  /// What kind of glare source the type is (None: glare(any luminaire) says why not).
  GlareShape::Kind glare_kind;
  /// What the luminaire is as a glare source (glare/glare_terms.cpp rates it): of glare_kind,
  /// or None for one that emits nothing.
  GlareShape (*glare)(const Luminaire& l);
  /// The effect a scene with this type needs (Results::effects; "point_emission"): see
  /// emission_effect() in scene_effects.hpp.
  const char* effect;
  /// A point of the luminaire in world coordinates, for the scene's centre.
  glm::dvec3 (*anchor)(const Luminaire& l);
  /// Where the luminaire is for placement (the optimizer, spacing rules): its position, or
  /// its parallelogram's centre.
  glm::dvec3 (*centre)(const Luminaire& l);
  /// Moves the luminaire so that centre() is `c`, keeping its shape and aim.
  void (*move_to)(Luminaire& l, const glm::dvec3& c);
  /// The field an aim design variable turns (`direction` or `aim`); nullptr when the type
  /// cannot be aimed (isotropic, or aimed by its shape).
  glm::dvec3* (*aim)(Luminaire& l);
  /// False for a type that is no object in the room (a sun's beam): spacing rules skip it.
  bool placed;
  /// Its direct light at receiver point `x` (local coordinates), drawn with `rng`; nullptr
  /// when its direct light is left to photons (sky and sun: their portals' light is not
  /// sampled from a point yet).
  LightSample (*direct)(const PreparedLuminaire& l, const glm::dvec3& x, PathRng& rng) = nullptr;
};

/// Reads a luminaire entry's keys ("name" and "type" already read): the keys every type may
/// have (`power_w`), then the row's own, which sees the entry without the common ones.
void read_luminaire_keys(const LuminaireType& row, const JsonNode& n, Luminaire& l,
                         const std::string& base_dir);

/// The spot profile (relative intensity at `theta` from the axis; half angles in radians).
double spot_profile(double theta, double half_beam, double half_field);

/// At most this many rows (tables sized at compile time: the scene analysis's effects).
inline constexpr std::size_t kMaxLuminaireTypes = 16;

/// All types, one row each.
std::span<const LuminaireType> luminaire_types();
/// The index of `type`'s row in luminaire_types().
std::size_t luminaire_type_index(Luminaire::Type type);
/// The row of `type`.
const LuminaireType& luminaire_type(Luminaire::Type type);

/// Where a luminaire "is" for placement: its type's centre() (position, or parallelogram centre).
inline glm::dvec3 anchor_of(const Luminaire& l) { return luminaire_type(l.type).centre(l); }
/// The row whose scene-file name is `name`, or nullptr.
const LuminaireType* find_luminaire_type(std::string_view name);
/// "point, spot, area, directional or photometric", for messages.
std::string luminaire_type_names();
/// The names of the types with an aim hook ("spot, directional or photometric").
std::string aimable_luminaire_type_names();

}  // namespace lightsolver::detail
