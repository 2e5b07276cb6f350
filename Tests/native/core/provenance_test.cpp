// Provenance of results (lightsolver/provenance.hpp): the canonical scene hash (indifferent to
// layout, not to values), the files a scene reads, what a run records (the same over thread
// counts where it should be), the JSON round trip, and verify_provenance's answers.
#include "lightsolver/provenance.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "lightsolver/results_io.hpp"
#include "lightsolver/run_options.hpp"
#include "lightsolver/scene_io.hpp"
#include "lightsolver/simulation.hpp"
#include "scene/provenance.hpp"
#include "scene_builders.hpp"
#include "scene_folder.hpp"

namespace lightsolver::test {
namespace {

TEST(Provenance, Sha256OfKnownText) {
  // FIPS 180-2, appendix B.1.
  EXPECT_EQ(detail::sha256_hex("abc"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(detail::sha256_hex(""),
            "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
}

TEST(Provenance, CanonicalTextIgnoresLayoutNotValues) {
  const auto canonical = [](const char* text) {
    return detail::canonical_json(nlohmann::json::parse(text));
  };
  const std::string base = canonical(R"({"b": [1, 2.5, "x"], "a": {"y": true, "x": null}})");
  EXPECT_EQ(base, R"({"a":{"x":null,"y":true},"b":[1,2.5,"x"]})");
  EXPECT_EQ(canonical("{\n  \"a\" : {\"x\":null, \"y\":true},\n\t\"b\":[1.0,2.5,\"x\"]}"), base);
  EXPECT_EQ(canonical(R"({"a": {"y": true, "x": null}, "b": [1e0, 25e-1, "x"]})"), base);
  EXPECT_EQ(canonical("[-0.0, 0, 1e15, 0.1]"), "[0,0,1000000000000000,0.1]");
  EXPECT_NE(canonical(R"({"b": [1, 2.5000001, "x"], "a": {"y": true, "x": null}})"), base);
  EXPECT_NE(canonical(R"({"b": [2.5, 1, "x"], "a": {"y": true, "x": null}})"), base);
  EXPECT_NE(canonical(R"({"b": [1, 2.5, "X"], "a": {"y": true, "x": null}})"), base);
}

TEST_F(SceneFolder, LoadedSceneKnowsItsContentAndFiles) {
  const Scene s = load_scene(scene_path());
  ASSERT_TRUE(s.source);
  EXPECT_EQ(s.source->sha256, detail::sha256_hex(detail::canonical_json(scene_)));
  // Each file once, in the order the scene names them, its path as written.
  ASSERT_EQ(s.source->files.size(), 3u);
  EXPECT_EQ(s.source->files[0].path, "floor.obj");
  EXPECT_EQ(s.source->files[0].kind, "mesh");
  EXPECT_EQ(s.source->files[1].path, "ies/down.ies");
  EXPECT_EQ(s.source->files[1].kind, "photometric");
  EXPECT_EQ(s.source->files[1].sha256, detail::sha256_hex(read(dir_ / "ies" / "down.ies")));
  EXPECT_EQ(s.source->files[2].path, "en12464-1.json");
  EXPECT_EQ(s.source->files[2].kind, "requirements table");
  // A re-indented file is the same content.
  save(scene_, -1);
  EXPECT_EQ(load_scene(scene_path()).source->sha256, s.source->sha256);
}

TEST_F(SceneFolder, RunRecordsEveryField) {
  const Results r = trace();
  ASSERT_TRUE(r.provenance);
  const Provenance& p = *r.provenance;
  EXPECT_EQ(p.scene_sha256, load_scene(scene_path()).source->sha256);
  EXPECT_EQ(p.files.size(), 3u);
  EXPECT_EQ(p.solver_version, version());
  EXPECT_FALSE(p.source_commit.empty());
  EXPECT_FALSE(p.build_type.empty());
  EXPECT_EQ(p.backend, "embree");
  EXPECT_NE(p.device.find("Embree"), std::string::npos) << p.device;
  EXPECT_EQ(p.mpi_ranks, 1);
  EXPECT_GE(p.threads, 1);
  EXPECT_EQ(p.command, "test");
  EXPECT_EQ(p.started_utc.size(), 20u);
  EXPECT_EQ(p.started_utc.back(), 'Z');
  EXPECT_LE(p.started_utc, p.finished_utc);
  EXPECT_FALSE(p.host.empty());
  // Every run option but threads and backend, by name, as resolved.
  std::vector<std::string> expected;
  for (const RunOptionInfo& o : run_option_infos()) {
    if (std::string(o.name) != "threads" && std::string(o.name) != "backend")
      expected.push_back(o.name);
  }
  std::sort(expected.begin(), expected.end());
  std::vector<std::string> names;
  for (const auto& [name, value] : p.options) names.push_back(name);
  EXPECT_EQ(names, expected);
  const auto option = [&](const char* name) {
    return std::find_if(p.options.begin(), p.options.end(),
                        [&](const auto& o) { return o.first == name; })
        ->second;
  };
  EXPECT_EQ(std::get<std::uint64_t>(option("photons")), 20000u);
  EXPECT_EQ(std::get<std::uint64_t>(option("seed")), 3u);
  EXPECT_EQ(std::get<double>(option("confidence")), r.confidence);
  EXPECT_TRUE(std::holds_alternative<std::monostate>(option("target_accuracy")));
}

// Threads change nothing a run's results hold but `threads` and the times.
TEST_F(SceneFolder, ThreadCountsChangeOnlyThreadsAndTimes) {
  Provenance one = *trace(1).provenance, three = *trace(3).provenance;
  EXPECT_EQ(one.threads, 1);
  EXPECT_EQ(three.threads, 3);
  for (Provenance* p : {&one, &three}) {
    p->threads = 0;
    p->started_utc = p->finished_utc = "";
  }
  EXPECT_EQ(detail::provenance_json(one), detail::provenance_json(three));
}

TEST_F(SceneFolder, ResultsReadBackWithTheirProvenance) {
  const std::string text = results_to_json(trace());
  const Results back = results_from_json(text, "r.json");
  ASSERT_TRUE(back.provenance);
  EXPECT_EQ(results_to_json(back), text);
  // Older results have none, and still read back to the same text.
  nlohmann::json old = nlohmann::json::parse(text);
  old.erase("provenance");
  const std::string old_text = old.dump(2) + "\n";
  const Results old_back = results_from_json(old_text);
  EXPECT_FALSE(old_back.provenance);
  EXPECT_EQ(results_to_json(old_back), old_text);
  // A malformed provenance is an error naming the field.
  nlohmann::json bad = nlohmann::json::parse(text);
  bad["provenance"]["files"][0].erase("sha256");
  try {
    results_from_json(bad.dump(), "r.json");
    FAIL() << "accepted a file without sha256";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("provenance.files[0]"), std::string::npos) << e.what();
  }
}

TEST_F(SceneFolder, VerifyAcceptsTheSameSceneReindented) {
  const std::string text = results_to_json(trace());
  EXPECT_TRUE(verify_results(scene_path(), text).empty());
  save(scene_, 8);  // another layout, the same content
  EXPECT_TRUE(verify_results(scene_path(), text).empty());
}

TEST_F(SceneFolder, VerifyNamesEachDifference) {
  const std::string text = results_to_json(trace());
  const auto says = [&](const std::vector<std::string>& lines, const std::string& part) {
    return std::any_of(lines.begin(), lines.end(),
                       [&](const std::string& l) { return l.find(part) != std::string::npos; });
  };
  // A value of the scene.
  nlohmann::json changed = scene_;
  changed["luminaires"][2]["flux_lm"] = 1001.0;
  save(changed);
  std::vector<std::string> d = verify_results(scene_path(), text);
  ASSERT_EQ(d.size(), 1u);
  EXPECT_TRUE(says(d, "scene's content differs"));
  save(scene_);
  // A photometric file's bytes (the scene text unchanged).
  write(dir_ / "ies" / "down.ies", read(dir_ / "ies" / "down.ies") + "\n");
  d = verify_results(scene_path(), text);
  ASSERT_EQ(d.size(), 1u) << d[0];
  EXPECT_TRUE(says(d, "photometric file \"ies/down.ies\" changed")) << d[0];
  // A missing mesh, and the requirements table changed.
  fs::remove(dir_ / "floor.obj");
  write(dir_ / "en12464-1.json", read(dir_ / "en12464-1.json") + " ");
  d = verify_results(scene_path(), text);
  EXPECT_EQ(d.size(), 3u);
  EXPECT_TRUE(says(d, "mesh file \"floor.obj\" is missing"));
  EXPECT_TRUE(says(d, "the requirements table \"en12464-1.json\" changed"));
}

TEST_F(SceneFolder, VerifyRefusesAnotherScenesResults) {
  const std::string text = results_to_json(trace());
  nlohmann::json other = scene_;
  other["luminaires"] = nlohmann::json::array(
      {{{"name", "bulb"}, {"type", "point"}, {"position", {2, 2, 2.5}}, {"flux_lm", 1000.0}}});
  write(dir_ / "other.json", other.dump(2));
  const std::vector<std::string> d = verify_results((dir_ / "other.json").string(), text);
  ASSERT_EQ(d.size(), 2u);
  EXPECT_NE(d[0].find("content differs"), std::string::npos);
  EXPECT_NE(d[1].find("\"ies/down.ies\", which the scene does not read now"), std::string::npos);
}

TEST_F(SceneFolder, ResultsWithoutAFileSceneCannotBeVerified) {
  nlohmann::json doc = nlohmann::json::parse(results_to_json(trace()));
  doc.erase("provenance");
  std::vector<std::string> d = verify_results(scene_path(), doc.dump());
  ASSERT_EQ(d.size(), 1u);
  EXPECT_NE(d[0].find("cannot be verified"), std::string::npos);
  // A scene changed in memory: no hash to compare with.
  Simulation sim(load_scene(scene_path()));
  ASSERT_TRUE(sim.scene().source);
  Luminaire brighter = sim.scene().luminaires[2];
  brighter.flux_lm *= 2;
  sim.set_luminaire(2, brighter);
  EXPECT_FALSE(sim.scene().source);
  SolveOptions o;
  o.photons = 10000;
  const Results r = sim.run(o);
  ASSERT_TRUE(r.provenance);
  EXPECT_FALSE(r.provenance->scene_sha256);
  d = verify_results(scene_path(), results_to_json(r));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_NE(d[0].find("built or changed in memory"), std::string::npos);
  EXPECT_NE(d[0].find("cannot be verified"), std::string::npos);
}

}  // namespace
}  // namespace lightsolver::test
