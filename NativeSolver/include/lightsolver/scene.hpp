#pragma once
/// \file scene.hpp
/// In-memory scene, format `lightsolver.scene/1` (docs/scene-format.md). Coordinates are kept
/// in double precision here; backends re-centre them before converting to float.

#include <cstdint>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "lightsolver/compliance.hpp"
#include "lightsolver/daylight.hpp"
#include "lightsolver/defaults.hpp"
#include "lightsolver/error.hpp"
#include "lightsolver/provenance.hpp"
#include "lightsolver/sunlight.hpp"

namespace lightsolver {

struct PhotometricData;    // photometry.hpp
class PhotometricSampler;  // photometry.hpp
namespace daylight {
class SkyEmitter;  // src/daylight/sky_sampler.hpp
}

/// Surface interaction model. Defaults are a diffuse material's (defaults.hpp); a mirror or
/// glossy material built in code sets its reflectance, as default_material() does.
struct Material {
  enum class Type { Diffuse, Mirror, Glass, Glossy };
  std::string name;
  Type type = Type::Diffuse;
  /// Lambertian (diffuse, glossy) or specular (mirror) albedo
  double reflectance = material_defaults::kDiffuseReflectance;
  double ior = material_defaults::kGlassIor;  ///< glass refractive index
  /// glass internal transmittance of one pass
  double transmittance = material_defaults::kGlassTransmittance;
  /// glass modelled as one sheet (a pane of two interfaces)
  bool thin = material_defaults::kGlassThin;
  double specular = material_defaults::kGlossySpecular;    ///< glossy lobe albedo
  double roughness = material_defaults::kGlossyRoughness;  ///< glossy roughness, GGX alpha = r^2
};

/// A material of `type` with every value a scene file may leave out at its default
/// (docs/scene-format.md): the reflectance is the type's (mirror 0.9, glossy 0, else 0.5).
inline Material default_material(std::string name, Material::Type type) {
  Material m;
  m.name = std::move(name);
  m.type = type;
  if (type == Material::Type::Mirror) m.reflectance = material_defaults::kMirrorReflectance;
  if (type == Material::Type::Glossy) m.reflectance = material_defaults::kGlossyReflectance;
  return m;
}

/// Triangle mesh in world coordinates (metres), transform already applied.
struct Mesh {
  std::string name;
  int material = 0;  ///< index into Scene::materials
  std::vector<glm::dvec3> vertices;
  std::vector<glm::u32vec3> triangles;
};

/// Glazing in a daylight opening (a sky's portal, a sun's opening; docs/daylight.md, "Glazing"):
/// τv at normal incidence (clear glass's angular shape, single or double panes), the glazed
/// fraction of the opening (frame factor) and the maintenance (dirt) factor, as EN 17037/DIALux.
struct GlazingDefinition {
  double transmittance = 1.0;
  int panes = 1;
  double frame_factor = 1.0;
  double maintenance_factor = 1.0;
};

/// Light source. Fields not used by a type keep their defaults.
/// A `sky` luminaire's sky (docs/scene-format.md, "sky"; docs/daylight.md, "Sky").
struct SkyDefinition {
  /// "cie" (a CIE standard general sky, `cie_type` 1..15), "cie_overcast" (Moon & Spencer),
  /// "uniform" or "perez".
  std::string model = "cie_overcast";
  int cie_type = 1;
  std::optional<glm::dvec3> sun_direction;  ///< toward the sun (z up), where the model needs it
  /// The level (CIE, overcast, uniform): exactly one of zenith luminance or diffuse horizontal
  /// illuminance of the unobstructed sky.
  std::optional<double> zenith_luminance_cd_m2, diffuse_horizontal_lx;
  /// Perez: diffuse horizontal and direct normal, in W/m² or (`perez_lux`) lx.
  double perez_diffuse_horizontal = 0.0, perez_direct_normal = 0.0;
  bool perez_lux = false;
  int day_of_year = 172;
  double dew_point_c = 11.0;
  double ground_reflectance = 0.2;    ///< the ground below the horizon
  double sun_direct_normal_lx = 0.0;  ///< the sun's light on the ground (CIE, overcast, uniform)
  /// Openings the sky shines through (edge1 x edge2 points into the room); none: from a disc
  /// covering the sphere of `site_radius_m` about `site_centre`.
  struct Portal {
    glm::dvec3 corner{0.0}, edge1{0.0}, edge2{0.0};
    std::optional<GlazingDefinition> glazing;  ///< none: an open hole
  };
  std::vector<Portal> portals;
  glm::dvec3 site_centre{0.0};
  double site_radius_m = 0.0;
  /// Only the light of one Reinhart sky patch (docs/daylight.md, "Daylight coefficients"):
  /// subdivision `mf`, patch `index` (0: the ground) in the frame whose true north is
  /// `north_deg` from +y (SkyPatches). Empty: the whole sky.
  struct Patch {
    int mf = 1;
    int index = 0;
    double north_deg = 0.0;
  };
  std::optional<Patch> patch;
};

struct Luminaire {
  enum class Type { Point, Spot, Area, Directional, Photometric, Sun, Sky };
  std::string name;
  Type type = Type::Point;
  double flux_lm = 0.0;            ///< emitted flux (directional: derived from illuminance_lx)
  glm::dvec3 position{0.0};        ///< point, spot, photometric
  glm::dvec3 direction{0, 0, -1};  ///< spot axis, directional beam (unit length)
  double beam_angle_deg = 0.0;     ///< spot: full angle at 50 % of peak intensity
  double field_angle_deg = 0.0;    ///< spot: full angle at 10 % of peak intensity
  glm::dvec3 corner{0.0}, edge1{0.0}, edge2{0.0};  ///< area / directional parallelogram
  double illuminance_lx = 0.0;                     ///< directional: illuminance normal to the beam
  /// Sun: where and when, when its beam's `direction` is computed from them (check() sets it);
  /// empty: `direction` is given. `time` is ISO 8601 with its zone; `north_deg` is the model's
  /// true north from +y, counter-clockwise seen from above (as `metadata.north_deg`).
  std::optional<Site> site;
  std::string time;
  double north_deg = 0.0;
  /// Sun: its position at `site` and `time` (check() fills it), for messages and results.
  std::optional<SunPosition> sun;
  /// Sun: the glazing of its opening (none: an open hole).
  std::optional<GlazingDefinition> glazing;
  /// Photometric: the distribution and its sampler (shared, immutable), the file it came from,
  /// and the luminaire frame: `aim` is where gamma = 0 points, `rotation_deg` turns the C0
  /// plane counter-clockwise about the luminaire's up axis (-aim; for a downlight: as seen from
  /// above). At 0, C0 points toward +x (toward +y when aiming along x). `flux_lm` is the flux
  /// actually emitted: the file's candela integrated, or scaled by a requested flux_lm over the
  /// file's lamp lumens (over the integrated flux for absolute photometry).
  std::shared_ptr<const PhotometricData> photometry;
  std::shared_ptr<const PhotometricSampler> sampler;
  std::string file;
  glm::dvec3 aim{0, 0, -1};
  double rotation_deg = 0.0;
  /// Electrical power (W), any type: read and range-checked, ignored by tracing (the report's
  /// luminaire schedule and W/m2 use it). Empty when not given.
  std::optional<double> power_w;
  /// Sky: its definition, and the sky with its portals as traced (built by validate(); its
  /// flux is flux_lm, and `position` the point it is anchored at). A sun through portals keeps
  /// them in `sky.portals` (the same objects as a sky's) instead of corner/edge1/edge2.
  SkyDefinition sky;
  std::shared_ptr<const daylight::SkyEmitter> sky_emitter;
  /// Control group (scene key `group`): luminaires of one group are dimmed together and their
  /// light is tallied apart from the other groups' (docs/statistics.md, "Groups"). Empty: the
  /// luminaire's own name, so each luminaire is its own group.
  std::string group;
  /// The group this luminaire belongs to: `group`, or its own name when that is empty.
  const std::string& group_name() const { return group.empty() ? name : group; }
};

/// Where illuminance is reported. An observer is an eye (docs/glare.md): the tracer tallies the
/// light reaching it after at least one reflection (its background luminance) and the results
/// give its UGR. An observer grid is many eyes (positions x view directions) and its maximum
/// UGR. Each type's keys, checks, tallies and results: types/target_types.cpp.
struct Target {
  enum class Type { Surface, Grid, Observer, ObserverGrid };
  std::string name;
  Type type = Type::Surface;
  int mesh = -1;                                   ///< surface: index into Scene::meshes
  glm::dvec3 corner{0.0}, edge1{0.0}, edge2{0.0};  ///< grid (observer grid) rectangle
  std::uint32_t nu = 1, nv = 1;                    ///< grid cells along edge1, edge2
  /// Observer: eye position (m), line of sight and up direction (unit length after validate();
  /// up is made orthogonal to the line of sight where it is used).
  glm::dvec3 position{0.0}, view_direction{0.0, 1.0, 0.0}, up{0.0, 0.0, 1.0};
  /// Observer grid: the eyes are `positions` or, when that is empty, the centres of the nu x nv
  /// cells of the rectangle corner, edge1, edge2 (put it at eye height). The lines of sight are
  /// `view_directions` or, with view_step_deg, every view_step_deg degrees about `up` starting
  /// from +x (docs/scene-format.md). Every eye looks in every direction.
  std::vector<glm::dvec3> positions, view_directions;
  std::optional<double> view_step_deg;
  /// What the target must reach (scene keys "requirements" and "task"); none when !any().
  Requirements requirements;
  /// What a grid reports besides lux (scene key `quantity`): a daylight-factor grid also gives
  /// the daylight factor of the scene's one sky (docs/daylight.md, "Daylight factor").
  enum class Quantity { Illuminance, DaylightFactor };
  Quantity quantity = Quantity::Illuminance;
  /// A grid that counts only light reflected at least once (no scene key: the annual run's twin
  /// of each grid, whose daylight coefficients' reflected part carries the sun's indirect light;
  /// docs/daylight.md, "Daylight coefficients").
  bool reflected_only = false;
};

/// A scene's run settings (scene file `settings`). Each member is a row of the run options
/// table (run_options.hpp), from which the scene reader, validate(), the CLI flags and the
/// Python keywords and Scene properties take their names, ranges and help; these initializers
/// are the defaults they all show.
struct Settings {
  std::uint64_t photons = 1'000'000;
  std::uint32_t max_bounces = 1000;
  std::uint64_t seed = 1;
  double confidence = 0.95;
  /// Time limit of the tracing (s, finite, > 0) of runs without an explicit photon count;
  /// unset: none, except accuracy runs (SolveOptions::max_seconds).
  std::optional<double> max_seconds;
  /// Accuracy goals of runs on this scene judge every grid cell, not only target means
  /// (SolveOptions::accuracy_per_cell).
  bool accuracy_per_cell = false;
  /// Trace until every requirement's verdict is decided (SolveOptions::decide).
  bool decide = false;
  /// Results carry each luminaire group's contribution per target and cell (`contributions`),
  /// which `rescale` needs (SolveOptions::contributions).
  bool contributions = false;
  /// Direct light at grids and surface targets by next-event estimation (shadow rays):
  /// "auto", "on" or "off" (SolveOptions::next_event; docs/statistics.md, "Next-event
  /// estimation"). A run's contributions carry the direct parts, so `rescale` and every other
  /// recombination of groups keep them. Default "auto".
  std::string next_event = "auto";
  /// Reflected light at grids by connecting photon vertices to the cells: "auto", "on" or
  /// "off" (SolveOptions::connect_reflections; docs/statistics.md, "Connected reflected
  /// light"). Its part is added to the groups' direct parts. Default "auto": where it can run
  /// (Embree, every surface diffuse, next-event estimation, a grid) and pays (enough connected
  /// light, paths not costlier than the photons).
  std::string connect_reflections = "auto";
};

/// A complete scene. Build it with load_scene(), from_json(), or field by field and validate().
struct Scene {
  std::string source_file;  ///< for messages; empty for in-memory scenes
  std::vector<Material> materials;
  std::vector<Mesh> meshes;
  std::vector<Luminaire> luminaires;
  std::vector<Target> targets;
  Settings settings;
  Warnings warnings;  ///< remarks made while loading (dropped triangles…)
  /// What the scene was read from (its content hash and the files it reads), for the results'
  /// provenance; absent for a scene built in memory. Changes in memory (Python's add_*,
  /// Simulation::set_luminaire) clear it: the scene is no longer the file's.
  std::optional<SceneSource> source;
  /// EN 17037 sunlight exposure to compute (the scene's `sunlight_exposure`; sunlight.hpp).
  std::optional<SunlightExposureSpec> sunlight_exposure;

  int find_material(const std::string& name) const;  ///< -1 when absent
  int find_mesh(const std::string& name) const;      ///< -1 when absent
  double total_flux_lm() const;                      ///< sum over luminaires
};

/// Flux of a directional luminaire: illuminance normal to the beam times the projected area.
double directional_flux_lm(const Luminaire& l);

/// Input ranges (docs/scene-format.md, "Ranges"). Values beyond them have no physical use and
/// are errors; within them every result is a finite number (docs/statistics.md).
namespace limits {
inline constexpr double kMinGridEdge_m = 1e-6;     ///< grid edges and grid cell edges: 1 um
inline constexpr double kMinArea_m2 = 1e-12;       ///< a grid cell, a surface target: (1 um)^2
inline constexpr double kMaxCoordinate_m = 1e9;    ///< |x|, |y|, |z| of points and edges
inline constexpr double kMaxFlux_lm = 1e12;        ///< one luminaire (also derived fluxes)
inline constexpr double kMaxIlluminance_lx = 1e7;  ///< directional (sunlight: ~1e5 lx)
inline constexpr double kMaxIntensity_cd = 1e15;   ///< photometric peak, as scaled
inline constexpr std::uint64_t kMaxGridCells = 10'000'000;  ///< one grid, and all grids together
inline constexpr std::uint32_t kMaxBounces = 1'000'000;     ///< settings.max_bounces
inline constexpr double kMaxPower_W = 1e9;                  ///< a luminaire's power_w
inline constexpr double kMaxRequiredIlluminance_lx = 1e7;   ///< requirements em_lux, emin_lux
inline constexpr double kMaxUgr = 40.0;  ///< requirements ugr_max: (0, 40] (EN 12464-1: 10..28)
/// An observer grid's positions x view directions: each is a tally square that every ray
/// segment is tested against, so tracing slows in proportion.
inline constexpr std::uint64_t kMaxObserverGridPoints = 1024;
}  // namespace limits

/// Throws InputError(file, where) unless 1 <= photons <= max_photons(max_bounces)
/// (statistics.hpp: at most 10^13, fewer where the 64-bit tallies could overflow).
void check_photon_count(std::uint64_t photons, std::uint32_t max_bounces, const std::string& file,
                        const std::string& where);

/// Checks every value (ranges, NaN, references, areas); drops degenerate triangles with a
/// warning. Throws InputError naming the field. Called by the loaders; call it yourself after
/// building a Scene by hand.
void validate(Scene& scene);

/// Checks (and normalises directions of) the luminaires only: for scenes changed in place.
void validate_luminaires(Scene& scene);

/// validate() that goes on after an error: every material, mesh, luminaire, target and the
/// settings are checked, and each one's first error is returned, in file order (empty: the
/// scene is valid). A surface target on a mesh with an error is not checked again.
std::vector<InputError> validation_errors(Scene& scene);

}  // namespace lightsolver

namespace lightsolver {

/// Spot profile: relative intensity (peak = 1) at `angle_rad` off the axis.
double spot_relative_intensity(const Luminaire& spot, double angle_rad);

/// Spot peak (on-axis) intensity in candela for the luminaire's flux.
double spot_peak_intensity_cd(const Luminaire& spot);

/// Photometric luminaire frame: the unit direction of its C0 plane (orthogonal to `aim`).
glm::dvec3 photometric_c0(const Luminaire& l);

/// Lamp output multiplier from the file's TILT table at the luminaire's tilt (the angle
/// between `aim` and straight down, -z); 1 without a table or for type A/B photometry, whose
/// measured attitude is not "aimed down". The solver emits flux_lm times this factor.
double photometric_tilt_factor(const Luminaire& l);

/// Remarks on a photometric luminaire for the results: its file's warnings, and a TILT table
/// that is not applied. Empty for other luminaire types.
Warnings photometric_warnings(const Luminaire& l);

/// Loads a photometric luminaire's file and sets `photometry`, `sampler` and `flux_lm` (the
/// requested flux, or the file's when `requested_flux_lm` is empty). Throws InputError naming
/// the file and line, or `where` for a bad flux.
void load_photometric(Luminaire& l, const std::string& path,
                      std::optional<double> requested_flux_lm, const std::string& where);

}  // namespace lightsolver
