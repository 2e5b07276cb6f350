// The scene analysis (prepare/scene_effects.hpp) and the Embree path kernels it picks
// (embree/path_kernel.hpp): each scene below switches one effect on or off, the analysis must
// say so, the backend must run the kernel it implies, and that kernel's tallies must equal the
// general kernel's to the bit for the same seed.
#include <gtest/gtest.h>

#include <cstdlib>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "model/backend.hpp"
#include "model/groups.hpp"
#include "model/prepared_scene.hpp"
#include "prepare/scene_effects.hpp"
#include "embree/embree_backend.hpp"
#include "embree/path_kernel.hpp"
#include "scene_builders.hpp"

namespace lightsolver::test {
namespace {

using detail::Effect;
using detail::KernelFeatures;

constexpr std::uint64_t kPhotons = 20'000, kSeed = 7;

Material glossy(double reflectance, double specular) {
  Material m;
  m.name = "glossy";
  m.type = Material::Type::Glossy;
  m.reflectance = reflectance;
  m.specular = specular;
  m.roughness = 0.3;
  return m;
}

Material glass(bool thin) {
  Material m;
  m.name = thin ? "pane" : "block glass";
  m.type = Material::Type::Glass;
  m.ior = 1.5;
  m.transmittance = 0.9;
  m.thin = thin;
  return m;
}

Target observer() {
  Target t;
  t.name = "eye";
  t.type = Target::Type::Observer;
  t.position = {2.0, 0.5, 1.2};
  t.view_direction = {0.0, 1.0, 0.0};
  return t;
}

// A 4 x 3 x 2.7 m room of reflectance `wall`, a spot, and (with_grid) a workplane grid; the
// room is a surface target when there is no grid.
Scene room(double wall, bool with_grid) {
  Scene s;
  add_material(s, "walls", Material::Type::Diffuse, wall);
  s.meshes.push_back(room_mesh("room", 0, dvec3(0), dvec3(4, 3, 2.7)));
  s.luminaires.push_back(spot_light({2, 1.5, 2.6}, {0.2, 0, -1}, 60, 100, 1000));
  s.luminaires.push_back(point_light({1, 1, 2.2}, 300));
  if (with_grid) {
    s.targets.push_back(grid("workplane", {0.5, 0.5, 0.8}, {3, 0, 0}, {0, 2, 0}, 6, 4));
  } else {
    s.targets.push_back(surface("room", 0));
  }
  return s;
}

// Adds a solid box of material `m` (a surface target) in the room's middle.
void add_block(Scene& s, const Material& m, dvec3 lo, dvec3 hi) {
  s.materials.push_back(m);
  const int material = static_cast<int>(s.materials.size() - 1);
  s.meshes.push_back(solid_box_mesh(m.name, material, lo, hi));
  s.targets.push_back(surface(m.name, static_cast<int>(s.meshes.size() - 1)));
}

void add_pane(Scene& s, const Material& m) {
  s.materials.push_back(m);
  const int material = static_cast<int>(s.materials.size() - 1);
  s.meshes.push_back(quad_mesh("pane", material, {0.5, 2.0, 0.2}, {3, 0, 0}, {0, 0, 2}));
}

struct Case {
  const char* name;
  Scene scene;
  KernelFeatures expected;
  std::vector<std::size_t> movable = {};
};

std::vector<Case> cases() {
  std::vector<Case> out;
  out.push_back({"diffuse with grid", room(0.6, true), {true, false, false, false, true}});
  out.push_back(
      {"diffuse, surface target only", room(0.6, false), {true, false, false, false, false}});
  Scene mirror = room(0.5, true);
  add_block(mirror, Material{"mirror", Material::Type::Mirror, 0.9}, {1, 1, 0}, {2, 2, 1});
  out.push_back({"mirror", std::move(mirror), {true, true, false, false, true}});
  Scene gloss = room(0.5, true);
  add_block(gloss, glossy(0.2, 0.5), {1, 1, 0}, {2, 2, 1});
  out.push_back({"glossy", std::move(gloss), {true, false, true, false, true}});
  Scene glassy = room(0.5, false);
  add_block(glassy, glass(false), {1, 1, 0.2}, {2, 2, 1.2});
  add_pane(glassy, glass(true));
  out.push_back({"glass (thick and thin)", std::move(glassy), {true, false, false, true, false}});
  Scene all = room(0.5, true);
  add_block(all, Material{"mirror", Material::Type::Mirror, 0.9}, {0.2, 0.2, 0}, {0.8, 0.8, 1});
  add_block(all, glossy(0.1, 0.6), {3, 2, 0}, {3.5, 2.5, 1});
  add_block(all, glass(false), {1, 1, 0.2}, {2, 2, 1.2});
  all.targets.push_back(observer());
  out.push_back({"every effect", std::move(all), detail::kGeneralKernel});
  Scene dark = room(0.0, true);
  dark.targets.push_back(observer());
  out.push_back(
      {"direct only, grid and observer", std::move(dark), {false, false, false, false, true}});
  out.push_back(
      {"direct only, surface target", room(0.0, false), {false, false, false, false, false}});
  Scene absorbing = room(0.5, true);  // present but black: no mirror or glossy code needed
  add_block(absorbing, Material{"black mirror", Material::Type::Mirror, 0.0}, {1, 1, 0}, {2, 2, 1});
  add_block(absorbing, glossy(0.0, 0.0), {3, 2, 0}, {3.5, 2.5, 1});
  out.push_back(
      {"black mirror and glossy", std::move(absorbing), {true, false, false, false, true}});
  out.push_back({"movable block (instanced)",
                 room_with_block({0.5, 0, 0}),
                 {true, false, false, false, true},
                 {1}});
  return out;
}

detail::TallyBlock trace(const detail::PreparedScene& p, detail::EmbreeKernel kernel,
                         const std::vector<std::size_t>& movable, KernelFeatures* ran = nullptr) {
  auto backend = detail::make_embree_backend(p, kernel);
  for (std::size_t m : movable) {
    backend->set_mesh_transform(m, glm::translate(glm::mat4(1.0f), glm::vec3(0.3f, 0.2f, 0.0f)));
  }
  if (ran) *ran = detail::embree_kernel(*backend);
  detail::TallyBlock t(p.groups.size() * p.bins.size());
  backend->trace(detail::group_ranges(p.groups, 0, kPhotons), kSeed, t);
  return t;
}

TEST(EmbreeKernels, EachSceneRunsItsKernelWithTheGeneralKernelsTallies) {
  for (Case& c : cases()) {
    SCOPED_TRACE(c.name);
    validate(c.scene);
    const detail::PreparedScene p = detail::prepare(c.scene, c.movable);
    EXPECT_TRUE(detail::kernel_for(detail::analyse_effects(p)) == c.expected);
    KernelFeatures ran;
    const detail::TallyBlock special = trace(p, detail::EmbreeKernel::Specialised, c.movable, &ran);
    EXPECT_TRUE(ran == c.expected);
    KernelFeatures general_ran;
    const detail::TallyBlock general =
        trace(p, detail::EmbreeKernel::General, c.movable, &general_ran);
    EXPECT_TRUE(general_ran == detail::kGeneralKernel);
    EXPECT_EQ(special.ray_segments, general.ray_segments);
    EXPECT_EQ(special.capped_paths, general.capped_paths);
    std::uint64_t hits = 0;
    for (std::size_t b = 0; b < p.bins.size(); ++b) {
      EXPECT_EQ(special.bins[b].sum, general.bins[b].sum) << "bin " << b;
      EXPECT_EQ(special.bins[b].sum_sq, general.bins[b].sum_sq) << "bin " << b;
      hits += general.bins[b].sum;
    }
    EXPECT_GT(hits, 0u);  // the scene's targets are lit: the comparison is not of zeros
    if (!c.expected.reflects) EXPECT_EQ(general.ray_segments, kPhotons);  // one per photon
  }
}

TEST(EmbreeKernels, EnvironmentForcesTheGeneralKernel) {
  Scene s = room(0.6, true);
  validate(s);
  const detail::PreparedScene p = detail::prepare(s);
  ::setenv("LIGHTSOLVER_EMBREE_KERNEL", "general", 1);
  const KernelFeatures forced = detail::embree_kernel(*detail::make_embree_backend(p));
  ::unsetenv("LIGHTSOLVER_EMBREE_KERNEL");
  EXPECT_TRUE(forced == detail::kGeneralKernel);
  const KernelFeatures chosen = detail::embree_kernel(*detail::make_embree_backend(p));
  EXPECT_TRUE(chosen == (KernelFeatures{true, false, false, false, true}));
}

TEST(SceneEffects, ListsEveryEffectOnceWithTheReasonForSkippingIt) {
  Scene s = room(0.5, true);
  add_block(s, Material{"black mirror", Material::Type::Mirror, 0.0}, {1, 1, 0}, {2, 2, 1});
  validate(s);
  const detail::PreparedScene p = detail::prepare(s);
  const detail::SceneEffects e = detail::analyse_effects(p);
  EXPECT_TRUE(e.has(Effect::Interreflection));
  EXPECT_TRUE(e.has(Effect::DiffuseReflection));
  EXPECT_FALSE(e.has(Effect::MirrorReflection));
  EXPECT_EQ(e.reason(Effect::MirrorReflection), "every mirror reflectance is 0");
  EXPECT_EQ(e.reason(Effect::GlossyReflection), "no glossy material");
  EXPECT_EQ(e.reason(Effect::Refraction), "no glass");
  EXPECT_TRUE(e.has(Effect::GridCrossing));
  EXPECT_TRUE(e.has(Effect::SurfaceTargets));
  EXPECT_EQ(e.reason(Effect::ObserverCrossing), "no observer");
  EXPECT_TRUE(e.has(detail::emission_effect(Luminaire::Type::Spot)) &&
              e.has(detail::emission_effect(Luminaire::Type::Point)));
  EXPECT_TRUE(e.has(Effect::LuminaireChoice));
  EXPECT_EQ(e.reason(detail::emission_effect(Luminaire::Type::Area)), "no area luminaire");
  const EffectsReport r = detail::effects_report(e);
  EXPECT_EQ(r.simulated.size() + r.skipped.size(), detail::effect_count());
  for (const SkippedEffect& k : r.skipped) EXPECT_FALSE(k.reason.empty()) << k.effect;
  // A run reports the same lists, and its text says what was left out and why.
  SolveOptions o;
  o.photons = 1000;
  o.backend = "embree";
  o.next_event = "off";  // the prepared scene above plans no next-event estimation
  const Results run = solve(s, o);
  EXPECT_EQ(run.effects.simulated, r.simulated);
  ASSERT_EQ(run.effects.skipped.size(), r.skipped.size());
  EXPECT_NE(results_table(run, true).find("no glass: refraction not simulated\n"), std::string::npos);
  const nlohmann::json j = nlohmann::json::parse(results_to_json(run));
  EXPECT_EQ(j["effects"]["simulated"].size(), r.simulated.size());
  const nlohmann::json glass = {{"effect", "refraction"}, {"reason", "no glass"}};
  const nlohmann::json& skipped = j["effects"]["skipped"];
  EXPECT_NE(std::find(skipped.begin(), skipped.end(), glass), skipped.end());
}

TEST(SceneEffects, AllBlackSurfacesMeanDirectLightOnly) {
  Scene s = room(0.0, true);
  validate(s);
  const detail::SceneEffects e = detail::analyse_effects(detail::prepare(s));
  EXPECT_FALSE(e.has(Effect::Interreflection));
  EXPECT_FALSE(e.has(Effect::DiffuseReflection));
  EXPECT_EQ(e.reason(Effect::DiffuseReflection), "every diffuse reflectance is 0");
  // Glass always returns some light (Fresnel), whatever its transmittance.
  add_pane(s, glass(true));
  validate(s);
  EXPECT_TRUE(detail::analyse_effects(detail::prepare(s)).has(Effect::Interreflection));
}

}  // namespace
}  // namespace lightsolver::test
