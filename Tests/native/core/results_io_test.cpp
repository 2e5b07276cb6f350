// The results JSON: every luminaire's traced flux (after TILT and a rescale's dimming) in the
// results, adding up to its group's flux; results_from_json the inverse of results_to_json
// (the golden results, results with requirements, contributions, observers and observer grids,
// rescaled results), with errors naming the field.
#include "lightsolver/results_io.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "lightsolver/error.hpp"
#include "lightsolver/photometry.hpp"
#include "lightsolver/rescale.hpp"
#include "scene_builders.hpp"

namespace lightsolver::test {
namespace {

// The parser corpus's TILT=INCLUDE lamp (type C; factor .90 at 45 degrees from straight down).
Luminaire tilt_lamp(const std::string& name, double tilt_deg, const std::string& group) {
  const double t = tilt_deg * std::numbers::pi / 180.0;
  Luminaire l;
  l.name = name;
  l.group = group;
  l.type = Luminaire::Type::Photometric;
  l.position = {2, 2, 2.5};
  l.aim = {std::sin(t), 0, -std::cos(t)};
  l.file = "lm63_1991_tilt_include.ies";
  load_photometric(l, std::string(LIGHTSOLVER_SOURCE_DIR) + "/Tests/fuzz/corpus/ies/" + l.file,
                   std::nullopt, "flux_lm");
  return l;
}

// A floor, a tilted TILT lamp and a point light in group "hall", a spot in its own group.
Scene tilt_scene() {
  Scene s;
  add_material(s, "grey", Material::Type::Diffuse, 0.5);
  s.meshes.push_back(quad_mesh("floor", 0, {0, 0, 0}, {4, 0, 0}, {0, 4, 0}));
  s.luminaires.push_back(tilt_lamp("tilted", 45.0, "hall"));
  s.luminaires.push_back(named(point_light({1, 1, 2.5}, 1200.0), "bulb", "hall"));
  s.luminaires.push_back(named(spot_light({3, 3, 2.5}, {0, 0, -1}, 30, 60, 800), "spot", ""));
  s.targets.push_back(surface("floor", 0));
  s.targets.push_back(grid("plane", {0, 0, 0.8}, {4, 0, 0}, {0, 4, 0}, 2, 2));
  s.settings.contributions = true;
  validate(s);
  return s;
}

Results run(const Scene& s) {
  SolveOptions o;
  o.photons = 20'000;
  o.seed = 3;
  return solve(s, o);
}

TEST(ResultsLuminaires, EachLuminairesTracedFluxIsInTheResults) {
  const Scene s = tilt_scene();
  const Results r = run(s);
  ASSERT_EQ(r.luminaires.size(), 3u);
  const LuminaireResult &tilted = r.luminaires[0], &bulb = r.luminaires[1], &spot = r.luminaires[2];
  EXPECT_EQ(tilted.name, "tilted");
  EXPECT_EQ(tilted.type, "photometric");
  EXPECT_EQ(tilted.group, "hall");
  EXPECT_EQ(tilted.flux_lm, s.luminaires[0].flux_lm);  // the file's own flux, before TILT
  EXPECT_NEAR(tilted.tilt_factor, 0.90, 1e-12);        // the table's value at 45 degrees
  EXPECT_EQ(tilted.dimming, 1.0);
  EXPECT_EQ(tilted.emitted_flux_lm, tilted.flux_lm * tilted.tilt_factor);
  EXPECT_LT(tilted.emitted_flux_lm, 0.95 * tilted.flux_lm);  // TILT changes it measurably
  EXPECT_EQ(bulb.type, "point");
  EXPECT_EQ(bulb.tilt_factor, 1.0);
  EXPECT_EQ(bulb.emitted_flux_lm, 1200.0);
  EXPECT_EQ(spot.group, "spot");  // its own group, named after it
  // The luminaires add up to their group's flux, bit for bit (the same sum in scene order),
  // and the groups to the total.
  ASSERT_EQ(r.groups.size(), 2u);
  EXPECT_EQ(r.groups[0].flux_lm, tilted.emitted_flux_lm + bulb.emitted_flux_lm);
  EXPECT_EQ(r.groups[1].flux_lm, spot.emitted_flux_lm);
  EXPECT_EQ(r.total_flux_lm, tilted.emitted_flux_lm + bulb.emitted_flux_lm + spot.emitted_flux_lm);

  const nlohmann::json j = nlohmann::json::parse(results_to_json(r));
  ASSERT_EQ(j.at("luminaires").size(), 3u);
  const nlohmann::json& first = j.at("luminaires")[0];
  EXPECT_EQ(first.at("name"), "tilted");
  EXPECT_EQ(first.at("group"), "hall");
  EXPECT_EQ(first.at("emitted_flux_lm").get<double>(), tilted.emitted_flux_lm);
  EXPECT_EQ(first.at("tilt_factor").get<double>(), tilted.tilt_factor);
  EXPECT_EQ(first.at("flux_lm").get<double>(), tilted.flux_lm);
  EXPECT_EQ(first.at("dimming").get<double>(), 1.0);
}

// A rescale dims each luminaire by its group's factor, and a second rescale by the product.
TEST(ResultsLuminaires, RescaleDimsEachLuminaireByItsGroupsFactor) {
  const Results r = run(tilt_scene());
  const std::string traced = results_to_json(r);
  const Results once = rescale_results(traced, {{"hall", 0.5}});
  ASSERT_EQ(once.luminaires.size(), 3u);
  EXPECT_EQ(once.luminaires[0].dimming, 0.5);
  EXPECT_EQ(once.luminaires[0].emitted_flux_lm, r.luminaires[0].emitted_flux_lm * 0.5);
  EXPECT_EQ(once.luminaires[0].tilt_factor, r.luminaires[0].tilt_factor);
  EXPECT_EQ(once.luminaires[2].dimming, 1.0);
  EXPECT_EQ(once.luminaires[2].emitted_flux_lm, r.luminaires[2].emitted_flux_lm);
  EXPECT_NEAR(once.groups[0].flux_lm,
              once.luminaires[0].emitted_flux_lm + once.luminaires[1].emitted_flux_lm,
              1e-12 * once.groups[0].flux_lm);
  const Results twice = rescale_results(results_to_json(once), {{"hall", 0.5}, {"spot", 0.0}});
  EXPECT_EQ(twice.luminaires[1].dimming, 0.25);
  EXPECT_EQ(twice.luminaires[1].emitted_flux_lm, 1200.0 * 0.25);
  EXPECT_EQ(twice.luminaires[2].emitted_flux_lm, 0.0);
  // Results written before the field: rescaled without it.
  nlohmann::json old = nlohmann::json::parse(traced);
  old.erase("luminaires");
  EXPECT_TRUE(rescale_results(old.dump(), {{"hall", 0.5}}).luminaires.empty());
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The CLI's files: every golden results file of a run reads back to the same text.
TEST(ResultsFromJson, GoldenResultsRoundTripToTheSameText) {
  for (const char* name : {"room", "office"}) {
    const std::string text =
        read_text(std::string(LIGHTSOLVER_SOURCE_DIR) + "/Tests/golden/" + name + ".results.json");
    ASSERT_FALSE(text.empty()) << name;
    const Results r = results_from_json(text, name);
    EXPECT_EQ(results_to_json(r), text) << name;
    EXPECT_FALSE(r.targets.empty()) << name;
  }
}

// An eye and an observer grid with requirements (verdicts, grid intervals), per-group
// contributions with their tallies and glare terms: every field reads back.
Scene glare_scene() {
  Scene s = tilt_scene();
  s.targets[1].requirements.em_lux = 100.0;
  s.targets[1].requirements.u0 = 0.4;
  Target eye;
  eye.name = "eye";
  eye.type = Target::Type::Observer;
  eye.position = {0.5, 2.0, 1.2};
  eye.view_direction = {1, 0, 0};
  eye.requirements.ugr_max = 19.0;
  s.targets.push_back(eye);
  Target eyes;
  eyes.name = "eyes";
  eyes.type = Target::Type::ObserverGrid;
  eyes.positions = {{0.5, 2.0, 1.2}, {3.5, 1.0, 1.2}};
  eyes.view_step_deg = 90.0;
  eyes.requirements.ugr_max = 19.0;
  s.targets.push_back(eyes);
  validate(s);
  return s;
}

TEST(ResultsFromJson, ResultsWithEveryPartRoundTrip) {
  const Results r = run(glare_scene());
  ASSERT_TRUE(r.judged && r.contributions);
  ASSERT_TRUE(r.targets[3].observer_grid && r.targets[2].glare);
  const std::string text = results_to_json(r);
  const Results back = results_from_json(text);
  EXPECT_EQ(results_to_json(back), text);
  // What a rescale and the statistics read, in the solver's order (not the JSON's key order).
  ASSERT_EQ(back.targets[1].verdicts.size(), r.targets[1].verdicts.size());
  for (std::size_t i = 0; i < r.targets[1].verdicts.size(); ++i) {
    EXPECT_EQ(back.targets[1].verdicts[i].name, r.targets[1].verdicts[i].name);
  }
  for (std::size_t i = 0; i < r.targets.size(); ++i) {
    ASSERT_EQ(back.targets[i].contributions.size(), r.groups.size());
    for (std::size_t g = 0; g < r.groups.size(); ++g) {
      const auto &a = back.targets[i].contributions[g], &b = r.targets[i].contributions[g];
      EXPECT_EQ(a.group, b.group);
      ASSERT_EQ(a.tallies.size(), b.tallies.size()) << r.targets[i].name;
      for (std::size_t k = 0; k < a.tallies.size(); ++k) {
        EXPECT_EQ(a.tallies[k].sum, b.tallies[k].sum);
        EXPECT_EQ(a.tallies[k].sum_sq, b.tallies[k].sum_sq);
      }
    }
  }
  EXPECT_EQ(back.targets[3].observer_grid->terms.status, r.targets[3].observer_grid->terms.status);
  EXPECT_EQ(back.targets[3].observer_grid->max_at, r.targets[3].observer_grid->max_at);
  // A rescaled result reads back too (`rescaled`, dimmed groups and luminaires).
  const std::string dimmed = rescale_results_json(text, {{"hall", 0.5}, {"spot", 0.0}});
  const Results again = results_from_json(dimmed);
  EXPECT_EQ(results_to_json(again), dimmed);
  ASSERT_EQ(again.rescaled.size(), 2u);
  EXPECT_EQ(again.rescaled[0], (std::pair<std::string, double>("hall", 0.5)));
}

TEST(ResultsFromJson, ErrorsNameTheFileAndField) {
  const std::string text = results_to_json(run(tilt_scene()));
  const auto message = [](const std::string& doc) {
    return input_error_of([&] { results_from_json(doc, "r.json"); });
  };
  nlohmann::json j = nlohmann::json::parse(text);
  j["format"] = "lightsolver.results/0";
  EXPECT_NE(message(j.dump()).find("format"), std::string::npos) << message(j.dump());
  j = nlohmann::json::parse(text);
  j["targets"][1]["min_lux"] = "low";
  EXPECT_NE(message(j.dump()).find("targets[1].min_lux"), std::string::npos) << message(j.dump());
  j = nlohmann::json::parse(text);
  j["targets"][1]["cells"].erase(0);
  EXPECT_NE(message(j.dump()).find("targets[1].cells"), std::string::npos) << message(j.dump());
  j = nlohmann::json::parse(text);
  j["luminaires"][0].erase("tilt_factor");
  EXPECT_NE(message(j.dump()).find("luminaires[0]"), std::string::npos) << message(j.dump());
  EXPECT_NE(message("{").find("r.json"), std::string::npos);
}

}  // namespace
}  // namespace lightsolver::test
