// Input ranges (docs/scene-format.md, "Ranges"): values beyond any physical use are errors
// naming the field; extreme values inside the ranges run and give finite results whose
// intervals contain their estimates.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "lightsolver/photometry.hpp"
#include "lightsolver/scene_io.hpp"
#include "scene_builders.hpp"

namespace lightsolver::test {
namespace {

const std::string kLuminaires = std::string(LIGHTSOLVER_SOURCE_DIR) + "/Resources/luminaires/";

void expect_finite_and_contained(const Estimate& e, const std::string& what) {
  EXPECT_TRUE(std::isfinite(e.mean) && std::isfinite(e.sigma) && std::isfinite(e.ci_low) &&
              std::isfinite(e.ci_high))
      << what << ": " << e.mean << " +- " << e.sigma << " [" << e.ci_low << ", " << e.ci_high
      << "]";
  EXPECT_GE(e.ci_low, 0.0) << what;
  EXPECT_LE(e.ci_low, e.mean) << what;
  EXPECT_LE(e.mean, e.ci_high) << what;
}

// Every number in the results is finite and every interval holds its estimate; the JSON has
// no null (nlohmann's rendering of NaN and infinity), inf or nan either.
void expect_sane(const Results& r, const std::string& what) {
  EXPECT_TRUE(std::isfinite(r.total_flux_lm)) << what;
  for (const TargetResult& t : r.targets) {
    const std::string w = what + ", " + t.name;
    EXPECT_TRUE(std::isfinite(t.area_m2) && t.area_m2 > 0.0) << w;
    expect_finite_and_contained(t.estimate, w);
    for (std::size_t c = 0; c < t.cells.size(); ++c) {
      expect_finite_and_contained(t.cells[c], w + " cell " + std::to_string(c));
    }
    if (t.is_grid) {
      EXPECT_TRUE(std::isfinite(t.min_lux) && std::isfinite(t.max_lux) &&
                  std::isfinite(t.uniformity))
          << w;
    }
  }
  Results bare = r;  // a scene built in memory has no content hash: provenance's null
  bare.provenance.reset();
  const std::string json = results_to_json(bare);
  for (const char* bad : {"null", "inf", "nan", "NaN"}) {
    EXPECT_EQ(json.find(bad), std::string::npos) << what << ": " << bad;
  }
}

Scene with_black(Scene s) {
  add_material(s, "black", Material::Type::Diffuse, 0.0);
  return s;
}

Luminaire directional(double lux, dvec3 corner, dvec3 e1, dvec3 e2) {
  Luminaire l;
  l.name = "sun";
  l.type = Luminaire::Type::Directional;
  l.direction = {0, 0, -1};
  l.corner = corner;
  l.edge1 = e1;
  l.edge2 = e2;
  l.illuminance_lx = lux;
  return l;
}

// Extreme scenes that are still accepted.
std::vector<std::pair<std::string, Scene>> extreme_scenes() {
  std::vector<std::pair<std::string, Scene>> out;
  {  // 10^12 lm, 0.1 mm above 1 um cells, and a single 1 um cell no photon may reach
    Scene s;
    s.luminaires.push_back(point_light({0, 0, 1e-4}, 1e12));
    s.targets.push_back(grid("1um cells", {-5e-5, -5e-5, 0}, {1e-4, 0, 0}, {0, 1e-4, 0}, 100, 100));
    s.targets.push_back(grid("1um grid", {-5e-7, -5e-7, 0}, {1e-6, 0, 0}, {0, 1e-6, 0}, 1, 1));
    out.emplace_back("max flux on the smallest cells", s);
  }
  {  // 10^-6 lm over a 10^9 m grid at the coordinate limit
    Scene s;
    s.luminaires.push_back(point_light({0, 0, 10}, 1e-6));
    s.targets.push_back(grid("huge", {-5e8, -5e8, 0}, {1e9, 0, 0}, {0, 1e9, 0}, 100, 100));
    out.emplace_back("tiny flux on a huge grid", s);
  }
  {  // 10^7 lx on 10^5 m2: 10^12 lm, every photon crosses the big grid once (p = 1)
    Scene s;
    s.luminaires.push_back(directional(1e7, {0, 0, 1}, {100, 0, 0}, {0, 1000, 0}));
    s.targets.push_back(grid("all", {0, 0, 0}, {100, 0, 0}, {0, 1000, 0}, 10, 10));
    s.targets.push_back(grid("1mm cells", {50, 500, 0}, {0.01, 0, 0}, {0, 0.01, 0}, 10, 10));
    out.emplace_back("max illuminance", s);
  }
  {  // closed black rooms: every path deposits exactly once on the room (p = 1)
    Scene s = with_black({});
    s.meshes.push_back(room_mesh("room", 0, dvec3(0), dvec3(4, 3, 2.5), 2));
    s.targets.push_back(surface("room", 0));
    s.luminaires.push_back(point_light({2, 1.5, 2}, 1e12));
    out.emplace_back("black room, 10^12 lm", s);
    Scene t = with_black({});
    t.meshes.push_back(room_mesh("room", 0, dvec3(0), dvec3(1e-5), 1));
    t.targets.push_back(surface("room", 0));
    t.luminaires.push_back(point_light(dvec3(5e-6), 1e-6));
    out.emplace_back("10 um black room, 10^-6 lm", t);
  }
  {  // many deposits per path: the per-path interval
    Scene s;
    add_material(s, "white", Material::Type::Diffuse, 0.99);
    s.meshes.push_back(room_mesh("room", 0, dvec3(0), dvec3(2), 1));
    s.targets.push_back(surface("room", 0));
    s.targets.push_back(grid("probe", {0.5, 0.5, 1}, {1, 0, 0}, {0, 1, 0}, 3, 2));
    s.luminaires.push_back(point_light(dvec3(1, 1, 1.5), 1e12));
    out.emplace_back("white room", s);
  }
  {  // a nearly parallel beam and a photometric luminaire at the flux limit
    Scene s;
    s.luminaires.push_back(spot_light({0, 0, 1}, {0, 0, -1}, 1e-3, 2e-3, 1e12));
    Luminaire p;
    p.name = "downlight";
    p.type = Luminaire::Type::Photometric;
    p.position = {0, 0, 1};
    load_photometric(p, kLuminaires + "downlight.ies", 9e11, "flux_lm");  // emits 9.008e11 lm
    s.luminaires.push_back(p);
    s.targets.push_back(grid("floor", {-1, -1, 0}, {2, 0, 0}, {0, 2, 0}, 4, 4));
    out.emplace_back("spot and photometric", s);
  }
  return out;
}

TEST(InputRanges, ExtremeAcceptedValuesGiveFiniteContainedResults) {
  for (auto [name, scene] : extreme_scenes()) {
    validate(scene);
    for (const double confidence : {0.5, 0.95, 0.999999}) {
      for (const std::uint64_t photons : {1ull, 2ull, 20'000ull}) {
        SolveOptions o;
        o.backend = "embree";
        o.photons = photons;
        o.confidence = confidence;
        const Results r = solve(scene, o);
        expect_sane(r, name + " @" + std::to_string(confidence) + " N=" + std::to_string(photons));
      }
    }
  }
}

TEST(InputRanges, EveryPathDepositingOnceGivesAnIntervalHoldingTheMean) {
  // The issue's case: a lamp in a closed black room, the room as target. Every path deposits
  // exactly once (p = 1), so the mean is exact and the upper end must equal it, not lie below.
  int checked = 0;
  for (auto [name, scene] : extreme_scenes()) {
    if (name.find("black room") == std::string::npos && name != "max illuminance") continue;
    ++checked;
    SolveOptions o;
    o.backend = "embree";
    o.photons = 50'000;
    o.next_event = "off";  // photon counts: next-event estimation would replace them
    const Results r = solve(scene, o);
    const Estimate& e = r.targets[0].estimate;
    ASSERT_EQ(e.hits, 50'000u) << name;
    EXPECT_TRUE(e.binomial) << name;
    EXPECT_DOUBLE_EQ(e.mean, r.total_flux_lm / r.targets[0].area_m2) << name;
    EXPECT_EQ(e.ci_high, e.mean) << name;
    EXPECT_LT(e.ci_low, e.mean) << name;
  }
  EXPECT_EQ(checked, 3);
}

// The message of the InputError that validate() throws, or "<no error>".
std::string error_of(Scene s) {
  try {
    validate(s);
  } catch (const InputError& e) {
    return e.what();
  }
  return "<no error>";
}

Scene lamp_over_grid() {
  Scene s;
  s.source_file = "ranges.json";
  s.luminaires.push_back(point_light({0, 0, 1}, 1000));
  s.targets.push_back(grid("g", {-1, -1, 0}, {2, 0, 0}, {0, 2, 0}, 2, 2));
  return s;
}

#define EXPECT_ERROR(scene, text)                                             \
  do {                                                                        \
    const std::string message_ = error_of(scene);                             \
    EXPECT_NE(message_.find(text), std::string::npos) << message_;            \
    EXPECT_NE(message_.find("ranges.json: "), std::string::npos) << message_; \
  } while (0)

TEST(InputRanges, TheBaseSceneIsValid) { EXPECT_EQ(error_of(lamp_over_grid()), "<no error>"); }

TEST(InputRanges, GridEdgeBelowOneMicrometre) {
  Scene s = lamp_over_grid();
  s.targets[0].edge1 = {1e-30, 0, 0};
  s.targets[0].edge2 = {0, 1e-30, 0};
  EXPECT_ERROR(s, "targets[0].edge1: is 1e-30 m long, shorter than 1 um");
  s.targets[0].edge1 = {2, 0, 0};
  s.targets[0].edge2 = {0, 9e-7, 0};
  EXPECT_ERROR(s, "targets[0].edge2: is 9e-07 m long");
}

TEST(InputRanges, GridCellEdgeBelowOneMicrometre) {
  Scene s = lamp_over_grid();
  s.targets[0].edge1 = {1e-3, 0, 0};
  s.targets[0].nu = 1001;  // 0.999 um cells
  EXPECT_ERROR(s, "targets[0].cells: cells of 9.99001e-07 x 1 m: a cell edge is shorter than 1 um");
  s.targets[0].nu = 1000;  // 1 um cells are accepted, a 1 mm cell all the more
  EXPECT_EQ(error_of(s), "<no error>");
}

TEST(InputRanges, GridCellAreaBelowOneSquareMicrometre) {
  Scene s = lamp_over_grid();
  s.targets[0].edge2 = {2, 1e-8, 0};  // nearly parallel edges: 2e-8 m2 in four cells
  s.targets[0].nu = s.targets[0].nv = 200;
  EXPECT_ERROR(s, "targets[0].cells: a cell's area is 5e-13 m2, below (1 um)^2");
}

TEST(InputRanges, GridCellCounts) {
  Scene s = lamp_over_grid();
  s.targets[0].nu = 0;
  EXPECT_ERROR(s, "targets[0].cells: need at least 1x1 cells");
  s.targets[0].nu = 10'000;
  s.targets[0].nv = 1001;
  s.targets[0].edge1 = s.targets[0].edge2 = {};
  s.targets[0].edge1.x = s.targets[0].edge2.y = 100;
  EXPECT_ERROR(s, "targets[0].cells: 10010000 cells, more than 10^7 in one grid");
  s.targets[0].nv = 600;  // 6e6 cells: accepted alone, but not twice
  EXPECT_EQ(error_of(s), "<no error>");
  s.targets.push_back(s.targets[0]);
  EXPECT_ERROR(s, "targets: the grids have 12000000 cells together, more than 10^7");
}

TEST(InputRanges, SurfaceTargetBelowOneSquareMicrometre) {
  Scene s = lamp_over_grid();
  add_material(s, "grey", Material::Type::Diffuse, 0.5);
  s.meshes.push_back(quad_mesh("speck", 0, {0, 0, 0}, {1e-7, 0, 0}, {0, 1e-7, 0}));
  s.targets.push_back(surface("speck", 0));
  EXPECT_ERROR(s, "targets[1].mesh: mesh \"speck\" has an area of 1e-14 m2");
}

TEST(InputRanges, CoordinatesBeyondOneBillionMetres) {
  Scene s = lamp_over_grid();
  s.luminaires[0].position.z = 2e9;
  EXPECT_ERROR(s, "luminaires[0].position: coordinate 2e+09 m is beyond 10^9 m");
  s = lamp_over_grid();
  s.targets[0].edge1 = {1e300, 0, 0};
  EXPECT_ERROR(s, "targets[0].edge1: coordinate 1e+300 m");
  s = lamp_over_grid();
  add_material(s, "grey", Material::Type::Diffuse, 0.5);
  s.meshes.push_back(quad_mesh("far", 0, {0, 0, -1.5e9}, {1, 0, 0}, {0, 1, 0}));
  EXPECT_ERROR(s, "meshes[0].vertices[0]: coordinate 1.5e+09 m");
}

TEST(InputRanges, FluxBeyondAnyLightSource) {
  Scene s = lamp_over_grid();
  s.luminaires[0].flux_lm = 1e308;
  EXPECT_ERROR(s, "luminaires[0].flux_lm: emits 1e+308 lm, more than 10^12 lm");
  s.luminaires[0].flux_lm = INFINITY;
  EXPECT_ERROR(s, "luminaires[0].flux_lm: must be a finite value >= 0 (got inf)");
  s.luminaires[0].flux_lm = 1e9;  // a stadium's worth
  EXPECT_EQ(error_of(s), "<no error>");
}

TEST(InputRanges, IlluminanceBeyondAnySun) {
  Scene s = lamp_over_grid();
  s.luminaires[0] = directional(1e300, {-1, -1, 1}, {2, 0, 0}, {0, 2, 0});
  EXPECT_ERROR(s, "luminaires[0].illuminance_lx: more than 10^7 lx (got 1e+300");
  s.luminaires[0].illuminance_lx = INFINITY;
  EXPECT_ERROR(s, "luminaires[0].illuminance_lx: must be a finite value >= 0");
  s.luminaires[0].illuminance_lx = 1e7;  // 10^7 lx on 10^6 m2 is 10^13 lm
  s.luminaires[0].edge1 = {1000, 0, 0};
  s.luminaires[0].edge2 = {0, 1000, 0};
  EXPECT_ERROR(s, "luminaires[0].illuminance_lx: the beam carries 1e+13 lm");
  s.luminaires[0].illuminance_lx = 1e5;  // the sun on a square kilometre
  EXPECT_EQ(error_of(s), "<no error>");
}

TEST(InputRanges, DirectionsTooLongToNormalise) {
  Scene s = lamp_over_grid();
  s.luminaires[0] = spot_light({0, 0, 1}, {1e200, 1e200, 0}, 20, 40, 100);
  EXPECT_ERROR(s, "luminaires[0].direction: too long to normalise");
}

// Writes a narrow (1 degree) IES distribution to a temporary file.
std::string narrow_ies(const std::string& lumens, const std::string& multiplier) {
  const auto path = std::filesystem::temp_directory_path() /
                    ("lightsolver_narrow_" + lumens + "_" + multiplier + ".ies");
  std::ofstream(path) << "IESNA:LM-63-2002\nTILT=NONE\n1 " << lumens << " " << multiplier
                      << " 3 1 1 2 0 0 0\n1 1 10\n0 0.5 1\n0\n1000 1000 0\n";
  return path.string();
}

Luminaire photometric_from(const std::string& path, std::optional<double> flux_lm) {
  Luminaire l;
  l.name = "narrow";
  l.type = Luminaire::Type::Photometric;
  l.position = {0, 0, 1};
  l.file = path;
  load_photometric(l, path, flux_lm, "flux_lm");
  return l;
}

TEST(InputRanges, PhotometricFluxAndIntensity) {
  // Guarding the product: emitted flux = integrated candela x flux_lm / lamp lumens.
  Scene s = lamp_over_grid();
  s.luminaires[0] = photometric_from(narrow_ies("1e-300", "1"), 1000.0);
  EXPECT_ERROR(s, "luminaires[0].flux_lm: emits");
  s.luminaires[0] = photometric_from(narrow_ies("1000", "1e200"), std::nullopt);
  EXPECT_ERROR(s, "more than 10^12 lm");
  // Absolute photometry scaled to 10^12 lm: the 1 degree beam peaks above 10^15 cd.
  s.luminaires[0] = photometric_from(narrow_ies("-1", "1"), 1e12);
  EXPECT_ERROR(s, "luminaires[0].file: peak intensity 1.");
  EXPECT_ERROR(s, "cd (as scaled) is more than 10^15 cd");
  s.luminaires[0] = photometric_from(narrow_ies("-1", "1"), 1e9);
  EXPECT_EQ(error_of(s), "<no error>");
}

TEST(InputRanges, MaxBounces) {
  Scene s = lamp_over_grid();
  s.settings.max_bounces = 1'000'001;
  EXPECT_ERROR(s, "settings.max_bounces: must be <= 1000000 (got 1000001)");
}

TEST(InputRanges, PhotonCountsAboveTheMaximum) {
  Scene s = lamp_over_grid();
  s.settings.photons = std::numeric_limits<std::uint64_t>::max();
  EXPECT_ERROR(s, "settings.photons: at most 10000000000000 photons in one run");
  s.settings.photons = kMaxPhotons;
  EXPECT_EQ(error_of(s), "<no error>");
  s.settings.max_bounces = 1'000'000;  // c <= 10^6 + 1 per path: Q could overflow sooner
  EXPECT_ERROR(s,
               "settings.photons: at most 18446707 photons in one run with max_bounces = 1000000");
  s.settings.photons = 18'446'707;
  EXPECT_EQ(error_of(s), "<no error>");
}

TEST(InputRanges, SolveOptionsAreCheckedLikeSettings) {
  Scene s = lamp_over_grid();
  validate(s);
  SolveOptions o;
  o.backend = "embree";
  o.photons = std::numeric_limits<std::uint64_t>::max();
  try {
    solve(s, o);
    FAIL() << "2^64 - 1 photons accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("photons: at most 10000000000000"), std::string::npos)
        << e.what();
  }
  o.photons = 100;
  o.confidence = 1.0;
  EXPECT_THROW(solve(s, o), InputError);
}

TEST(InputRanges, ConfidenceBelowOneHalfWarns) {
  Scene s = lamp_over_grid();
  s.settings.confidence = 0.3;
  validate(s);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("settings.confidence: 0.3 gives intervals narrower"),
            std::string::npos);
}

TEST(InputRanges, FileLevelChecks) {
  const std::string scene = R"({"format": "lightsolver.scene/1", "materials": {}, "meshes": [],
    "luminaires": [{"name": "l", "type": "point", "flux_lm": 1000, "position": [0,0,1]}],
    "targets": [{"name": "g", "type": "grid", "corner": [-1,-1,0], "edge1": [2,0,0],
                 "edge2": [0,2,0], "cells": CELLS}],
    "settings": {"photons": PHOTONS}})";
  auto error = [&](const std::string& cells, const std::string& photons) -> std::string {
    std::string text = scene;
    text.replace(text.find("CELLS"), 5, cells);
    text.replace(text.find("PHOTONS"), 7, photons);
    try {
      scene_from_json(text, "ranges.json", ".");
    } catch (const InputError& e) {
      return e.what();
    }
    return "<no error>";
  };
  EXPECT_EQ(error("[2, 2]", "1000"), "<no error>");
  EXPECT_NE(error("[2, 2]", "18446744073709551615").find("ranges.json: settings.photons: at most"),
            std::string::npos);
  // 2^32 x 2^32 wraps to 0 in 64 bits: each factor is checked before the product.
  EXPECT_NE(error("[4294967296, 4294967296]", "1000")
                .find("ranges.json: targets[0].cells: more than 10^7 cells in one grid"),
            std::string::npos);
  EXPECT_NE(error("[3163, 3163]", "1000").find("targets[0].cells: more than 10^7"),
            std::string::npos);
}

}  // namespace
}  // namespace lightsolver::test
