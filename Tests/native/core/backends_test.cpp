// The backend registry: it lists exactly the backends built (checked against the build's own
// LIGHTSOLVER_HAVE_VULKAN, not against the registry), every name it lists traces on the backend
// of that name, and an unknown name is refused with the registry's names.
#include "lightsolver/backends.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "lightsolver/error.hpp"
#include "scene_builders.hpp"

namespace lightsolver::test {
namespace {

std::vector<std::string> expected_names() {
#ifdef LIGHTSOLVER_HAVE_VULKAN
  return {"auto", "embree", "vulkan"};
#else
  return {"auto", "embree"};
#endif
}

Scene lit_floor() {
  Scene s;
  const int grey = add_material(s, "grey", Material::Type::Diffuse, 0.5);
  s.meshes.push_back(quad_mesh("floor", grey, {0, 0, 0}, {2, 0, 0}, {0, 2, 0}));
  s.luminaires.push_back(point_light({1, 1, 1}, 1000.0));
  s.targets.push_back(surface("floor", 0));
  return s;
}

TEST(BackendRegistry, ListsAutoThenExactlyTheBackendsBuilt) {
  EXPECT_EQ(backend_names(), expected_names());
  const std::vector<BackendInfo> list = lightsolver::backends();
  ASSERT_EQ(list.size(), expected_names().size());
  EXPECT_EQ(list.front().name, kAutoBackend);
  for (const BackendInfo& b : list) {
    EXPECT_FALSE(b.description.empty()) << b.name;
    EXPECT_FALSE(b.available.has_value()) << b.name << ": backends() must not probe devices";
    EXPECT_EQ(b.gpu, b.name == "vulkan") << b.name;
  }
}

TEST(BackendRegistry, AutoDescriptionNamesTheBackendsItChoosesFrom) {
  const std::string text = lightsolver::backends().front().description;
  for (const std::string& name : backend_names()) {
    if (name != kAutoBackend) EXPECT_NE(text.find(name), std::string::npos) << text;
  }
}

TEST(BackendRegistry, AvailabilityIsProbedAndEmbreeIsAlwaysThere) {
  const std::vector<BackendInfo> list = available_backends();
  ASSERT_EQ(list.size(), expected_names().size());
  for (const BackendInfo& b : list) ASSERT_TRUE(b.available.has_value()) << b.name;
  EXPECT_TRUE(*list[0].available);  // auto: some backend can start
  EXPECT_EQ(list[1].name, "embree");
  EXPECT_TRUE(*list[1].available);
}

// Every name the registry lists traces, on the backend of that name; an available backend
// starts, one reported unavailable fails with an error instead of tracing elsewhere.
TEST(BackendRegistry, EveryListedNameTracesOnThatBackend) {
  for (const BackendInfo& b : available_backends()) {
    if (b.name == kAutoBackend) continue;
    if (!*b.available) {
      EXPECT_THROW(run_on_backend(b.name, lit_floor(), 1000, 1), std::runtime_error) << b.name;
      continue;
    }
    const Results r = run_on_backend(b.name, lit_floor(), 20'000, 1);
    EXPECT_EQ(r.backend, b.name);
    EXPECT_EQ(r.photons, 20'000u);
    EXPECT_GT(r.targets.at(0).estimate.mean, 0.0) << b.name;
  }
  const std::string chosen = run_on_backend(kAutoBackend, lit_floor(), 1000, 1).backend;
  EXPECT_NE(std::find(expected_names().begin(), expected_names().end(), chosen),
            expected_names().end())
      << chosen;
}

TEST(BackendRegistry, UnknownNameIsAnInputErrorListingTheRegistry) {
  try {
    run_on_backend("cuda", lit_floor(), 10, 1);
    FAIL() << "no error for an unknown backend";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.where(), "backend") << what;
    EXPECT_NE(what.find("\"cuda\""), std::string::npos) << what;
    for (const std::string& name : expected_names())
      EXPECT_NE(what.find(name), std::string::npos) << name << " missing from: " << what;
  }
}

}  // namespace
}  // namespace lightsolver::test
