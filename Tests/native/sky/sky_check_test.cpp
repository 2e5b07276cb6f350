// `lightsolver check` on a sky without portals (src/prepare/scene_check.cpp): a scene reaching
// beyond the site's sphere is warned about (those points miss part of the sky), and so is a site
// far larger than the scene (few photons can reach it); a site that fits draws no remark.
#include <gtest/gtest.h>

#include "lightsolver/scene_check.hpp"
#include "sky_rooms.hpp"

namespace lightsolver::test {
namespace {

std::vector<std::string> site_warnings(double radius, bool with_portal = false) {
  Scene s;
  add_material(s, "grey", Material::Type::Diffuse, 0.5);
  s.meshes.push_back(quad_mesh("floor", 0, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}));
  s.targets.push_back(grid("floor", {0, 0, 0.01}, {1, 0, 0}, {0, 1, 0}, 1, 1));
  Luminaire l = sky("uniform", 1000.0);
  l.sky.site_centre = {0.5, 0.5, 0};
  l.sky.site_radius_m = radius;
  if (with_portal) l.sky.portals.push_back({{0, 0, 3}, {0, 1, 0}, {1, 0, 0}, std::nullopt});
  s.luminaires.push_back(l);
  std::vector<std::string> out;
  for (const SceneIssue& w : check_scene(s).warnings) {
    if (w.field == "luminaires[0].site") out.push_back(w.message);
  }
  return out;
}

TEST(SkyCheck, WarnsWhenTheSceneLeavesTheSitesSphere) {
  const auto w = site_warnings(0.5);  // the floor's corners are 0.71 m from the centre
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("reaches 0.7 m from the site's centre, beyond its radius_m 0.5 m"),
            std::string::npos)
      << w[0];
}

TEST(SkyCheck, WarnsWhenFewPhotonsCanReachTheScene) {
  const auto w = site_warnings(100.0);  // the scene lies within 0.71 m: (0.71/100)² = 0.005 %
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("at most 0.005 % of the sky's photons can reach the scene"),
            std::string::npos)
      << w[0];
  EXPECT_NE(w[0].find("portals"), std::string::npos);
}

TEST(SkyCheck, SilentWhenTheSiteFitsOrPortalsAreGiven) {
  EXPECT_TRUE(site_warnings(1.0).empty());  // 0.71 m inside 1 m, half the photons can reach it
  EXPECT_TRUE(site_warnings(100.0, true).empty());
}

// The side-lit room of sky_luminaire_test (a 1.5 x 1.2 m window in a 3 x 3 x 2.5 m room): lit
// from the site's disc, `check` says it is a closed room with openings and names portals; with
// its window's portal, or without the window (no opening: nothing to point at), it says nothing.
std::vector<std::string> room_warnings(bool window, bool portal) {
  Scene s;
  add_material(s, "grey", Material::Type::Diffuse, 0.5);
  const Hole hole = window ? Hole{0.32, 0.8, 0.25, 0.75} : Hole{0, 0, 0, 0};
  s.meshes.push_back(room_with_hole(0, {0, 0, 0}, {3, 3, 2.5}, false, hole));
  s.targets.push_back(grid("floor", {0.25, 0.25, 0.8}, {2.5, 0, 0}, {0, 2.5, 0}, 2, 2));
  Luminaire l = sky("uniform", 1000.0);
  l.sky.site_centre = {1.5, 1.5, 1.25};
  l.sky.site_radius_m = 2.6;
  if (portal) l.sky.portals.push_back({{0.75, 0, 0.8}, {0, 0, 1.2}, {1.5, 0, 0}, std::nullopt});
  s.luminaires.push_back(l);
  std::vector<std::string> out;
  for (const SceneIssue& w : check_scene(s).warnings) {
    if (w.field == "luminaires[0].portals") out.push_back(w.message);
  }
  return out;
}

TEST(SkyCheck, WarnsAboutAClosedRoomWithOpeningsButNoPortals) {
  const auto w = room_warnings(true, false);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("closed room with openings but no portals: from target \"floor\" only"),
            std::string::npos)
      << w[0];
  EXPECT_TRUE(room_warnings(true, true).empty());
  EXPECT_TRUE(room_warnings(false, false).empty());
}

}  // namespace
}  // namespace lightsolver::test
