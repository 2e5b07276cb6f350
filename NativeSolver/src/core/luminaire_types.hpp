#pragma once
// One row per luminaire type: how the scene file spells it, how it is read, checked, prepared
// and emitted on the CPU. The reader (scene_json.cpp), the validator (scene.cpp), prepare()
// (prepared_scene.cpp) and the CPU emitter (emitters.hpp) look the type up here instead of
// switching over Luminaire::Type. The GPU has its own row per type (vulkan/gpu_scene.cpp,
// Shaders/emit.glsl): docs/solver.md, "Adding a luminaire type".
#include <glm/vec3.hpp>
#include <span>
#include <string>
#include <string_view>

#include "core/prepared_scene.hpp"
#include "lightsolver/scene.hpp"

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

/// One luminaire type. Every hook is required.
struct LuminaireType {
  Luminaire::Type type;
  const char* name;  ///< "type" in the scene file
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
};

/// Reads a luminaire entry's keys ("name" and "type" already read): the keys every type may
/// have (`power_w`), then the row's own, which sees the entry without the common ones.
void read_luminaire_keys(const LuminaireType& row, const JsonNode& n, Luminaire& l,
                         const std::string& base_dir);

/// The spot profile (relative intensity at `theta` from the axis; half angles in radians).
double spot_profile(double theta, double half_beam, double half_field);

/// All types, one row each.
std::span<const LuminaireType> luminaire_types();
/// The row of `type`.
const LuminaireType& luminaire_type(Luminaire::Type type);
/// The row whose scene-file name is `name`, or nullptr.
const LuminaireType* find_luminaire_type(std::string_view name);
/// "point, spot, area, directional or photometric", for messages.
std::string luminaire_type_names();
/// The names of the types with an aim hook ("spot, directional or photometric").
std::string aimable_luminaire_type_names();

}  // namespace lightsolver::detail
