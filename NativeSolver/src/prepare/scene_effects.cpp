#include "prepare/scene_effects.hpp"

#include <algorithm>

namespace lightsolver::detail {
namespace {

using M = Material::Type;

constexpr std::size_t kFirstEmission = static_cast<std::size_t>(Effect::kFirstEmission);
// The effects before the emission effects (those are named by the luminaire types' rows).
constexpr const char* kNames[kFirstEmission] = {
    "interreflection", "diffuse_reflection", "mirror_reflection", "glossy_reflection",
    "refraction",      "surface_targets",    "grid_crossing",     "observer_crossing",
    "instancing",      "luminaire_choice",   "next_event_direct", "reflection_connection"};

// Chance that a photon leaves a surface of this material at all (before any geometry). Glass
// always reflects some light (Fresnel), so it always counts as returning light.
bool returns_light(const Material& m) {
  switch (m.type) {
    case M::Diffuse:
    case M::Mirror:
      return m.reflectance > 0.0;
    case M::Glossy:
      return m.reflectance + m.specular > 0.0;
    case M::Glass:
      return true;
  }
  return true;
}

// The materials photons can hit: those of meshes with triangles.
std::vector<const Material*> hit_materials(const PreparedScene& s) {
  std::vector<const Material*> out;
  for (const PreparedMesh& m : s.meshes) {
    if (!m.indices.empty()) out.push_back(&s.materials[m.material]);
  }
  return out;
}

// One material kind: on when some hit material of the kind returns light. The reason tells
// "no mirror" from "every mirror's reflectance is 0".
void set_material_effect(SceneEffects& e, Effect effect, M type, const char* kind,
                         const std::vector<const Material*>& used) {
  bool present = false, reflects = false;
  for (const Material* m : used) {
    if (m->type != type) continue;
    present = true;
    reflects = reflects || returns_light(*m);
  }
  std::string reason = present ? std::string("every ") + kind + " reflectance is 0"
                               : std::string("no ") + kind + " material";
  e.set(effect, reflects, std::move(reason));
}

// Each luminaire type's emission: on when a luminaire of the type is present.
void set_luminaire_effects(SceneEffects& e, const PreparedScene& s) {
  e.set(Effect::LuminaireChoice, s.luminaires.size() > 1, "one luminaire");
  const bool next_event = std::any_of(s.groups.begin(), s.groups.end(),
                                      [](const PreparedGroup& g) { return g.next_event; });
  e.set(Effect::NextEventDirect, next_event, s.next_event_off);
  const bool connect = std::any_of(s.groups.begin(), s.groups.end(),
                                   [](const PreparedGroup& g) { return g.connect; });
  e.set(Effect::ReflectionConnection, connect, s.connect_off);
  for (const LuminaireType& row : luminaire_types()) {
    const bool used =
        std::any_of(s.luminaires.begin(), s.luminaires.end(),
                    [&row](const PreparedLuminaire& l) { return l.type == row.type; });
    e.set(emission_effect(row.type), used, std::string("no ") + row.name + " luminaire");
  }
}

}  // namespace

std::size_t effect_count() { return kFirstEmission + luminaire_types().size(); }

Effect emission_effect(Luminaire::Type type) {
  return static_cast<Effect>(kFirstEmission + luminaire_type_index(type));
}

const char* effect_name(Effect e) {
  const auto i = static_cast<std::size_t>(e);
  return i < kFirstEmission ? kNames[i] : luminaire_types()[i - kFirstEmission].effect;
}

void SceneEffects::set(Effect e, bool on, std::string reason_if_off) {
  on_[index(e)] = on;
  reasons_[index(e)] = on ? std::string() : std::move(reason_if_off);
}

SceneEffects analyse_effects(const PreparedScene& s) {
  SceneEffects e;
  const std::vector<const Material*> used = hit_materials(s);
  set_material_effect(e, Effect::DiffuseReflection, M::Diffuse, "diffuse", used);
  set_material_effect(e, Effect::MirrorReflection, M::Mirror, "mirror", used);
  set_material_effect(e, Effect::GlossyReflection, M::Glossy, "glossy", used);
  const bool glass =
      std::any_of(used.begin(), used.end(), [](const Material* m) { return m->type == M::Glass; });
  e.set(Effect::Refraction, glass, "no glass");
  const bool reflects =
      std::any_of(used.begin(), used.end(), [](const Material* m) { return returns_light(*m); });
  e.set(Effect::Interreflection, reflects,
        "every reflectance is 0 (direct light only, one segment per photon)");
  const bool surface_bins = std::any_of(s.meshes.begin(), s.meshes.end(),
                                        [](const PreparedMesh& m) { return m.bin >= 0; });
  e.set(Effect::SurfaceTargets, surface_bins, "no surface target");
  const bool grids = std::any_of(s.grids.begin(), s.grids.end(),
                                 [](const PreparedGrid& g) { return !g.indirect_only; });
  e.set(Effect::GridCrossing, grids, "no grid target");
  const bool observers = std::any_of(s.grids.begin(), s.grids.end(),
                                     [](const PreparedGrid& g) { return g.indirect_only; });
  e.set(Effect::ObserverCrossing, observers, "no observer");
  const bool movable = std::any_of(s.meshes.begin(), s.meshes.end(),
                                   [](const PreparedMesh& m) { return m.movable; });
  e.set(Effect::Instancing, movable, "no movable mesh");
  set_luminaire_effects(e, s);
  return e;
}

EffectsReport effects_report(const SceneEffects& effects) {
  EffectsReport r;
  for (std::size_t i = 0; i < effect_count(); ++i) {
    const auto e = static_cast<Effect>(i);
    if (effects.has(e)) {
      r.simulated.emplace_back(effect_name(e));
    } else {
      r.skipped.push_back({effect_name(e), effects.reason(e)});
    }
  }
  return r;
}

}  // namespace lightsolver::detail
