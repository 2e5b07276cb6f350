// Start-up's fast paths give what the general ones give (issue 28, "Start in milliseconds"):
// the direct PLY reader and Assimp the same meshes, the streamed scene hash the canonical text's
// hash, inline meshes the same values and the same errors; and the --timings recorder records
// only while enabled and sums repeated phases; a loaded scene's meshes are checked once, and
// everything else as validating twice did.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "io/json_fast.hpp"
#include "io/json_reader.hpp"
#include "lightsolver/error.hpp"
#include "lightsolver/scene_io.hpp"
#include "lightsolver/timings.hpp"
#include "scene/mesh_io.hpp"
#include "scene/provenance.hpp"
#include "scene/validate_again.hpp"
#include "scene_builders.hpp"

namespace lightsolver::test {
namespace {

namespace fs = std::filesystem;

const fs::path kExamples = fs::path(LIGHTSOLVER_SOURCE_DIR) / "Examples" / "optimization";

std::string file_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// A folder of its own under the temp directory, removed afterwards.
class TempFolder {
 public:
  TempFolder() : path_(fs::temp_directory_path() / ("startup_test_" + std::to_string(::getpid()))) {
    fs::create_directories(path_);
  }
  ~TempFolder() { fs::remove_all(path_); }
  fs::path file(const std::string& name, const std::string& bytes) const {
    std::ofstream(path_ / name, std::ios::binary) << bytes;
    return path_ / name;
  }

 private:
  fs::path path_;
};

TEST(StartupPly, DirectReaderGivesAssimpsMeshOnEveryExamplePly) {
  int files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(kExamples)) {
    if (entry.path().extension() != ".ply") continue;
    ++files;
    const std::string path = entry.path().string();
    const std::optional<Mesh> direct = detail::read_simple_ply(path);
    ASSERT_TRUE(direct.has_value()) << path << ": the workbench's layout, read directly";
    const Mesh assimp = detail::read_mesh_with_assimp(path);
    ASSERT_EQ(direct->vertices.size(), assimp.vertices.size()) << path;
    ASSERT_EQ(direct->triangles.size(), assimp.triangles.size()) << path;
    EXPECT_TRUE(direct->vertices == assimp.vertices) << path;
    EXPECT_TRUE(direct->triangles == assimp.triangles) << path;
  }
  EXPECT_GE(files, 8);
}

// One binary PLY of one triangle or quad, as the workbench writes it (`face_count` vertices).
std::string binary_ply(int face_count, std::int32_t last_index = 2) {
  std::string header =
      "ply\nformat binary_little_endian 1.0\ncomment by a test\nelement vertex 4\n"
      "property float x\nproperty float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n";
  const float v[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  std::string bytes = header + std::string(reinterpret_cast<const char*>(v), sizeof v);
  bytes += static_cast<char>(face_count);
  for (std::int32_t i = 0; i < face_count; ++i) {
    const std::int32_t index = i + 1 == face_count ? last_index : i;
    bytes += std::string(reinterpret_cast<const char*>(&index), 4);
  }
  return bytes;
}

TEST(StartupPly, OtherLayoutsAreLeftToAssimp) {
  TempFolder folder;
  const fs::path triangle = folder.file("t.ply", binary_ply(3));
  const std::optional<Mesh> direct = detail::read_simple_ply(triangle.string());
  ASSERT_TRUE(direct.has_value());
  EXPECT_EQ(direct->vertices.size(), 4u);
  ASSERT_EQ(direct->triangles.size(), 1u);
  EXPECT_EQ(direct->triangles[0], glm::u32vec3(0, 1, 2));
  // A quad is Assimp's to triangulate; a bad index, a truncated file and ASCII are its too.
  EXPECT_FALSE(detail::read_simple_ply(folder.file("q.ply", binary_ply(4, 3)).string()));
  EXPECT_EQ(load_mesh_file(folder.file("q2.ply", binary_ply(4, 3)).string()).triangles.size(), 2u);
  EXPECT_FALSE(detail::read_simple_ply(folder.file("i.ply", binary_ply(3, 9)).string()));
  EXPECT_FALSE(detail::read_simple_ply(folder.file("i2.ply", binary_ply(3, -1)).string()));
  const std::string whole = binary_ply(3);
  EXPECT_FALSE(
      detail::read_simple_ply(folder.file("c.ply", whole.substr(0, whole.size() - 1)).string()));
  EXPECT_FALSE(detail::read_simple_ply(
      folder
          .file("a.ply",
                "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
          .string()));
}

TEST(StartupHash, StreamedHashIsTheCanonicalTextsHash) {
  const char* texts[] = {
      R"({"b": [1, 2.5, "x"], "a": {"y": true, "x": null}})",
      R"({"n": [-0.0, 0.0, -1, -1.0, 1e3, 1.5e300, -2.5e-300, 9007199254740992.0, 1e16,
                18446744073709551615, -9223372036854775808, 0.1, 3.0000000000000004]})",
      R"({"s": ["caf\u00e9", "tab\t", "quote\"", "\u0001", "Büro"], "": {}, "e": []})",
  };
  for (const char* text : texts) {
    const nlohmann::json doc = nlohmann::json::parse(text);
    EXPECT_EQ(detail::canonical_sha256(doc), detail::sha256_hex(detail::canonical_json(doc)))
        << text;
  }
  for (const char* name : {"conference/conference.json", "cornell/cornell.json"}) {
    const nlohmann::json doc = nlohmann::json::parse(file_text(kExamples / name));
    EXPECT_EQ(detail::canonical_sha256(doc), detail::sha256_hex(detail::canonical_json(doc)))
        << name;
  }
}

// Same values of the same JSON types all the way down (== alone calls 1 and 1u equal).
bool identical(const nlohmann::json& a, const nlohmann::json& b) {
  if (a.type() != b.type() || a != b) return false;
  if (a.is_object()) {
    for (auto i = a.begin(), j = b.begin(); i != a.end(); ++i, ++j) {
      if (i.key() != j.key() || !identical(*i, *j)) return false;
    }
  }
  if (a.is_array()) {
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (!identical(a[i], b[i])) return false;
    }
  }
  return true;
}

TEST(StartupJson, FastParserBuildsNlohmannsDocument) {
  const std::string texts[] = {
      R"({"a": [1, -1, 0, -0, 1.0, -0.0, 1e3, 1E-3, 2.5e+300, 4.9e-324, 0.30000000000000004,
          18446744073709551615, 18446744073709551616, -9223372036854775808,
          -9223372036854775809, 123456789012345678901234567890], "b": {"x": "y"},
          "a": "the later key stands", "t": true, "f": false, "n": null, "e": [], "o": {}})",
      " \t\r\n"
      R"(["caf\u00e9", "Büro", "tab\t", "\ud83d\ude00", "q\""])"
      " \n",
      "42",
      R"("text")",
      "[[[[[]]]]]",
  };
  for (const std::string& text : texts) {
    const std::optional<nlohmann::json> fast = detail::parse_json_fast(text);
    ASSERT_TRUE(fast.has_value()) << text;
    EXPECT_TRUE(identical(*fast, nlohmann::json::parse(text))) << text;
  }
  int files = 0;  // every JSON file of the source tree
  for (const char* folder : {"Examples", "Tests", "Resources", "docs"}) {
    for (const auto& entry :
         fs::recursive_directory_iterator(fs::path(LIGHTSOLVER_SOURCE_DIR) / folder)) {
      const fs::path& p = entry.path();
      if (p.extension() != ".json") continue;
      const std::string text = file_text(p);
      const std::optional<nlohmann::json> fast = detail::parse_json_fast(text);
      try {
        const nlohmann::json doc = nlohmann::json::parse(text);
        ASSERT_TRUE(fast.has_value()) << p;
        EXPECT_TRUE(identical(*fast, doc)) << p;
        ++files;
      } catch (const nlohmann::json::exception&) {  // a test's malformed file
        EXPECT_FALSE(fast.has_value()) << p;
      }
    }
  }
  EXPECT_GE(files, 20);
}

TEST(StartupJson, AnythingElseIsLeftToNlohmannAndItsMessages) {
  const std::string texts[] = {
      "",           "{",           "[1,]",
      R"({"a" 1})", "01",          "1.",
      "-",          ".5",          "+1",
      "1e",         "[1 2]",       "nul",
      "truex",      "{} {}",       "1e400",
      "-1e400",     "1e-400",      "\xEF\xBB\xBF{}",
      "\"\x01\"",   "\"\xff\"",    R"("\x")",
      R"(["a])",    R"({"a":1,})", std::string(300, '[') + std::string(300, ']'),
  };
  for (const std::string& text : texts) {
    EXPECT_FALSE(detail::parse_json_fast(text).has_value()) << text;
    std::string nlohmann_says, ours;
    try {
      nlohmann_says = nlohmann::json::parse(text).dump();
    } catch (const nlohmann::json::exception& e) {
      nlohmann_says = std::string("error: ") + e.what();
    }
    try {
      ours = detail::parse_json_text(text, "f.json").dump();
    } catch (const InputError& e) {
      ours = "error";
    }
    // The same document where nlohmann reads one (1e-400 is 0, a BOM is skipped), an error
    // where it has one.
    EXPECT_EQ(ours.rfind("error", 0), nlohmann_says.rfind("error", 0)) << text;
    if (ours.rfind("error", 0) != 0) EXPECT_EQ(ours, nlohmann_says) << text;
  }
}

std::string scene_with_mesh(const std::string& vertices, const std::string& triangles) {
  return R"({"format": "lightsolver.scene/1", "materials": {"m": {"type": "diffuse",
    "reflectance": 0.5}}, "luminaires": [{"name": "l", "type": "point", "position": [0, 0, 2],
    "flux_lm": 100}], "targets": [{"name": "t", "type": "surface", "mesh": "floor"}], "meshes": [{"name": "floor", "material": "m",
    "vertices": )" +
         vertices + R"(, "triangles": )" + triangles + "}]}";
}

TEST(StartupInlineMesh, ValuesAndErrorsAsBefore) {
  const Scene s = scene_from_json(
      scene_with_mesh("[[0, 0, 0], [1.5, 0, 0], [0, 2e0, 0.25]]", "[[0, 1, 2], [2, 1.0, 0]]"),
      "s.json", ".");
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].vertices[1], glm::dvec3(1.5, 0, 0));
  EXPECT_EQ(s.meshes[0].vertices[2], glm::dvec3(0, 2, 0.25));
  EXPECT_EQ(s.meshes[0].triangles[1], glm::u32vec3(2, 1, 0));  // 1.0 is an index too
  const auto error = [](const std::string& v, const std::string& t) {
    return input_error_of([&] { scene_from_json(scene_with_mesh(v, t), "s.json", "."); });
  };
  const std::string ok_v = "[[0, 0, 0], [1, 0, 0], [0, 1, 0]]";
  EXPECT_NE(error("[[0, 0, 0], [1, 0], [0, 1, 0]]", "[[0, 1, 2]]").find("meshes[0].vertices[1]"),
            std::string::npos);
  EXPECT_NE(error("[[0, 0, 0], [1, \"a\", 0], [0, 1, 0]]", "[[0, 1, 2]]")
                .find("meshes[0].vertices[1][1]"),
            std::string::npos);
  EXPECT_NE(error(ok_v, "[[0, 1, 3]]").find("meshes[0].triangles[0][2]: vertex index 3 out of"),
            std::string::npos);
  EXPECT_NE(error(ok_v, "[[0, -1, 2]]").find("meshes[0].triangles[0][1]: must be >= 0"),
            std::string::npos);
  EXPECT_NE(error(ok_v, "[[0, 1]]").find("meshes[0].triangles[0]: expected [i, j, k]"),
            std::string::npos);
  EXPECT_NE(error(ok_v, "[7]").find("meshes[0].triangles[0]: expected an array"),
            std::string::npos);
}

// The CLI's Simulation does not check a loaded scene's mesh geometry again
// (Simulation::Options::scene_validated): the rest is validated again, so the values that
// validation normalises are the same to the bit as after two validations (the results were).
TEST(StartupValidate, MeshesOnceEverythingElseAsBefore) {
  const fs::path root(LIGHTSOLVER_SOURCE_DIR);
  for (const char* file : {"Tests/golden/scenes/lamps.json", "Examples/room/room.json",
                           "Examples/daylight/side_lit_room.scene.json"}) {
    Scene twice = load_scene((root / file).string()), again = twice;
    validate(twice);
    detail::validate_again(again);
    ASSERT_EQ(twice.luminaires.size(), again.luminaires.size());
    for (std::size_t i = 0; i < twice.luminaires.size(); ++i) {
      const Luminaire &a = twice.luminaires[i], &b = again.luminaires[i];
      EXPECT_TRUE(a.direction == b.direction && a.aim == b.aim && a.position == b.position &&
                  a.flux_lm == b.flux_lm && a.corner == b.corner && a.edge1 == b.edge1)
          << file << " luminaire " << i;
    }
    for (std::size_t i = 0; i < twice.targets.size(); ++i) {
      const Target &a = twice.targets[i], &b = again.targets[i];
      EXPECT_TRUE(a.view_direction == b.view_direction && a.up == b.up &&
                  a.view_directions == b.view_directions && a.positions == b.positions)
          << file << " target " << i;
    }
    EXPECT_EQ(twice.warnings, again.warnings) << file;
  }
  // What validate_again still refuses, with validate()'s message; and a mesh vertex out of
  // range (validate() builds its field path only for the error now): its path and message.
  Scene s = load_scene((root / "Examples/room/room.json").string());
  Scene bad_material = s;
  bad_material.meshes[1].material = 99;
  EXPECT_THROW(detail::validate_again(bad_material), InputError);
  Scene far = s;
  far.meshes[1].vertices[3].z = 2e9;
  try {
    validate(far);
    FAIL() << "a vertex 2e9 m out accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("meshes[1].vertices[3]: coordinate 2e+09 m is beyond"),
              std::string::npos)
        << e.what();
  }
}

TEST(StartupTimings, RecordsOnlyWhenEnabledAndSumsRepeats) {
  if (!timings::enabled()) {
    { const timings::Scope quiet("not recorded"); }
    EXPECT_TRUE(timings::phases().empty());
  }
  timings::enable();
  {
    const timings::Scope outer("outer");
    std::thread([] { const timings::Scope side("side", 1); }).join();
    for (int i = 0; i < 3; ++i) const timings::Scope inner("inner");
    timings::mark("point");
  }
  const std::vector<timings::Phase> phases = timings::phases();
  ASSERT_EQ(phases.size(), 6u);
  EXPECT_EQ(phases.back().name, "outer");
  EXPECT_EQ(phases.back().depth, 0);
  EXPECT_EQ(phases.front().depth, 1);
  const std::string text = timings::format(phases);
  EXPECT_NE(text.find("\n  outer "), std::string::npos) << text;
  EXPECT_NE(text.find("\n    inner (x3) "), std::string::npos) << text;
  EXPECT_NE(text.find("\n    point "), std::string::npos) << text;
  // The other thread's phase after the ones nested under its parent, at its depth.
  EXPECT_LT(text.find("\n    point "), text.find("\n    side "));
  EXPECT_GE(timings::cpu_ms_before_enable(), 0.0);
}

}  // namespace
}  // namespace lightsolver::test
