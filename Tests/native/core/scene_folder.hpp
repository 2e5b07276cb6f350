#pragma once
// A scene folder of its own for provenance tests (provenance_test.cpp,
// combined_provenance_test.cpp): a mesh file, a photometric file, the requirements table and
// the scene, pretty-printed.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "lightsolver/scene_io.hpp"
#include "lightsolver/solver.hpp"

namespace lightsolver::test {

namespace fs = std::filesystem;

inline void write(const fs::path& p, const std::string& text) {
  std::ofstream(p, std::ios::binary) << text;
}

inline std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A scene folder of its own: a mesh file, a photometric file, the requirements table (a target
// names a task) and the scene, pretty-printed.
class SceneFolder : public ::testing::Test {
 protected:
  void SetUp() override {
    // One folder per test and process: suites of two builds may run at the same time.
    const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    dir_ = fs::temp_directory_path() / ("provenance_" + test + "_" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "ies");
    const std::string src = LIGHTSOLVER_SOURCE_DIR;
    fs::copy_file(std::string(LIGHTSOLVER_TEST_DATA) + "/quad.obj", dir_ / "floor.obj");
    fs::copy_file(src + "/Resources/luminaires/downlight.ies", dir_ / "ies" / "down.ies");
    fs::copy_file(src + "/Resources/requirements/en12464-1.json", dir_ / "en12464-1.json");
    scene_ = nlohmann::json::parse(R"({
      "format": "lightsolver.scene/1",
      "materials": {"grey": {"type": "diffuse", "reflectance": 0.5}},
      "meshes": [{"name": "floor", "material": "grey", "file": "floor.obj",
                  "transform": [[4, 0, 0, 0], [0, 4, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]}],
      "luminaires": [
        {"name": "d1", "type": "photometric", "file": "ies/down.ies", "position": [1, 1, 2.5]},
        {"name": "d2", "type": "photometric", "file": "ies/down.ies", "position": [3, 3, 2.5]},
        {"name": "bulb", "type": "point", "position": [2, 2, 2.5], "flux_lm": 1000.0}],
      "targets": [{"name": "floor", "type": "surface", "mesh": "floor"},
                  {"name": "desk", "type": "grid", "corner": [0, 0, 0.8], "edge1": [4, 0, 0],
                   "edge2": [0, 4, 0], "cells": [2, 2], "task": "office-writing"}],
      "settings": {"photons": 20000, "seed": 3}})");
    save(scene_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  void save(const nlohmann::json& doc, int indent = 2) const {
    write(scene_path(), doc.dump(indent));
  }
  std::string scene_path() const { return (dir_ / "scene.json").string(); }

  Results trace(int threads = 0) const {
    SolveOptions o;
    o.threads = threads;
    o.backend = "embree";
    o.command = "test";
    return solve(load_scene(scene_path()), o);
  }

  fs::path dir_;
  nlohmann::json scene_;
};

}  // namespace lightsolver::test
