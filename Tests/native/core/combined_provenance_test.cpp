// Provenance of results combined from group traces (Simulation::combine, the optimizer's reused
// traces): the scene's source and the traces' run facts as run() records them, every group's
// factor in `rescaled` as a rescale records it, and verify's rule for such results (the scene's
// content and files as traced, the flux record the solver's: accepted with the factors noted;
// another scene, an edited flux record or a scene changed in memory: refused).
#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "lightsolver/provenance.hpp"
#include "lightsolver/results_io.hpp"
#include "lightsolver/simulation.hpp"
#include "scene/provenance.hpp"
#include "scene_folder.hpp"

namespace lightsolver::test {
namespace {

constexpr std::uint64_t kPhotons = 30000;

// The folder's scene in a Simulation, every group traced with `seed` (group g with seed + g
// when `seeds_differ`).
class Combined : public SceneFolder {
 protected:
  void SetUp() override {
    SceneFolder::SetUp();
    sim_ = std::make_unique<Simulation>(load_scene(scene_path()),
                                        Simulation::Options{"embree", 2, {}});
  }
  void trace_all(std::uint64_t seed, bool seeds_differ = false) {
    traces_.clear();
    for (std::size_t g = 0; g < sim_->groups().size(); ++g) {
      traces_.push_back(sim_->trace_group(g, kPhotons, seeds_differ ? seed + g : seed));
    }
  }
  // Every group's trace (null where `fluxes` is 0) combined at `fluxes`.
  Results combine(const std::vector<double>& fluxes) const {
    std::vector<const GroupTrace*> parts;
    for (std::size_t g = 0; g < traces_.size(); ++g) {
      parts.push_back(fluxes[g] > 0.0 ? &traces_[g] : nullptr);
    }
    return sim_->combine(parts, fluxes, 0.95);
  }
  std::vector<double> scene_fluxes() const {
    std::vector<double> out;
    for (const LuminaireGroup& g : sim_->groups()) out.push_back(g.flux_lm);
    return out;
  }
  std::vector<std::string> notes_of(const Results& r) const {
    const Verification v = verify_document(scene_path(), results_to_json(r), "r.json");
    EXPECT_TRUE(v.differences.empty()) << v.differences.front();
    return v.notes;
  }

  std::unique_ptr<Simulation> sim_;
  std::vector<GroupTrace> traces_;
};

TEST_F(Combined, CarryTheScenesSourceAndTheTracesRunFacts) {
  trace_all(5);
  const Results r = combine(scene_fluxes());
  ASSERT_TRUE(r.provenance);
  const Provenance& p = *r.provenance;
  const SceneSource now = scene_file_source(scene_path());
  EXPECT_EQ(p.scene_sha256, now.sha256);
  ASSERT_EQ(p.files.size(), now.files.size());
  for (std::size_t i = 0; i < p.files.size(); ++i)
    EXPECT_EQ(p.files[i].sha256, now.files[i].sha256);
  EXPECT_EQ(p.backend, "embree");
  EXPECT_FALSE(p.device.empty());
  EXPECT_EQ(p.threads, 2);
  EXPECT_EQ(p.mpi_ranks, 1);
  EXPECT_LE(p.started_utc, p.finished_utc);
  EXPECT_NE(p.command.find("Simulation::combine"), std::string::npos);
  // The options as a run of the same photons and seed resolves them, but what combine does not
  // do (decide, contributions: the scene's settings are false here as well).
  SolveOptions o;
  o.photons = kPhotons;
  o.seed = 5;
  o.backend = "embree";
  const Results run = sim_->run(o);
  EXPECT_EQ(detail::provenance_json(p)["options"],
            detail::provenance_json(*run.provenance)["options"]);
  EXPECT_EQ(detail::provenance_json(p)["files"], detail::provenance_json(*run.provenance)["files"]);
  // Every group's factor, 1 at the scene's fluxes: the same trace, as traced.
  ASSERT_EQ(r.rescaled.size(), sim_->groups().size());
  for (const auto& [name, factor] : r.rescaled) EXPECT_EQ(factor, 1.0) << name;
  EXPECT_TRUE(notes_of(r).empty());
}

TEST_F(Combined, OtherGroupFluxesAreRecordedAsARescaleRecordsThem) {
  trace_all(5);
  std::vector<double> fluxes = scene_fluxes();  // d1, d2, bulb
  ASSERT_EQ(fluxes.size(), 3u);
  const double d2 = fluxes[1];
  fluxes[1] = 0.0;   // dark: no trace
  fluxes[2] *= 0.5;  // the bulb at half
  const Results r = combine(fluxes);
  const std::vector<std::pair<std::string, double>> expected{
      {"d1", 1.0}, {"d2", 0.0}, {"bulb", 0.5}};
  EXPECT_EQ(r.rescaled, expected);
  EXPECT_EQ(r.groups[2].flux_lm, fluxes[2]);
  EXPECT_EQ(r.luminaires[2].dimming, 0.5);
  EXPECT_EQ(r.luminaires[1].emitted_flux_lm, 0.0);
  EXPECT_GT(d2, 0.0);
  // Read back and written again: the same text (the record survives a round trip).
  const std::string text = results_to_json(r);
  EXPECT_EQ(results_to_json(results_from_json(text, "r.json")), text);
  // Accepted for the traced scene, the factors that are not 1 named.
  const std::vector<std::string> notes = notes_of(r);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("\"bulb\" x 0.5"), std::string::npos) << notes[0];
  EXPECT_NE(notes[0].find("\"d2\" x 0"), std::string::npos) << notes[0];
  EXPECT_EQ(notes[0].find("\"d1\""), std::string::npos) << notes[0];
}

TEST_F(Combined, VerifyRefusesAnotherSceneAndAnEditedFluxRecord) {
  trace_all(5);
  std::vector<double> fluxes = scene_fluxes();
  fluxes[2] *= 0.5;
  const std::string text = results_to_json(combine(fluxes));
  // Another scene: the bulb brighter in the file (the same geometry, other inputs).
  nlohmann::json brighter = scene_;
  brighter["luminaires"][2]["flux_lm"] = 2000.0;
  write(dir_ / "brighter.json", brighter.dump(2));
  Verification v = verify_document((dir_ / "brighter.json").string(), text, "r.json");
  ASSERT_EQ(v.differences.size(), 1u);
  EXPECT_NE(v.differences[0].find("content differs"), std::string::npos);
  EXPECT_TRUE(v.notes.empty());
  // The record edited: the bulb's dimming no longer its group's factor, and a group's flux no
  // longer its luminaires' sum.
  nlohmann::json edited = nlohmann::json::parse(text);
  edited["luminaires"][2]["dimming"] = 1.0;
  v = verify_document(scene_path(), edited.dump(), "r.json");
  ASSERT_EQ(v.differences.size(), 1u);
  EXPECT_NE(
      v.differences[0].find("luminaire \"bulb\" is dimmed by 1 but its group \"bulb\" by 0.5"),
      std::string::npos)
      << v.differences[0];
  edited = nlohmann::json::parse(text);
  edited["groups"][0]["flux_lm"] = 5.0;
  v = verify_document(scene_path(), edited.dump(), "r.json");
  ASSERT_EQ(v.differences.size(), 1u);
  EXPECT_NE(v.differences[0].find("group \"d1\" emits 5 lm"), std::string::npos)
      << v.differences[0];
  edited = nlohmann::json::parse(text);
  edited["rescaled"]["hall"] = 1.0;
  v = verify_document(scene_path(), edited.dump(), "r.json", /*validate=*/false);
  ASSERT_EQ(v.differences.size(), 1u);
  EXPECT_NE(v.differences[0].find("\"hall\", which they do not hold"), std::string::npos);
}

TEST_F(Combined, TracesOfASceneChangedInMemoryCannotBeVerified) {
  Luminaire moved = sim_->scene().luminaires[2];
  moved.position.x += 0.5;
  sim_->set_luminaire(2, moved);
  trace_all(5);
  const Results r = combine(scene_fluxes());
  ASSERT_TRUE(r.provenance);
  EXPECT_FALSE(r.provenance->scene_sha256);
  const std::vector<std::string> d = verify_results(scene_path(), results_to_json(r));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_NE(d[0].find("cannot be verified"), std::string::npos);
}

// Threads change nothing combined results hold but `threads` and the times.
TEST_F(Combined, ThreadCountsChangeOnlyThreadsAndTimes) {
  trace_all(5);
  Provenance two = *combine(scene_fluxes()).provenance;
  sim_ =
      std::make_unique<Simulation>(load_scene(scene_path()), Simulation::Options{"embree", 1, {}});
  trace_all(5);
  const Results r = combine(scene_fluxes());
  Provenance one = *r.provenance;
  EXPECT_EQ(one.threads, 1);
  EXPECT_EQ(two.threads, 2);
  for (Provenance* p : {&one, &two}) {
    p->threads = 0;
    p->started_utc = p->finished_utc = "";
  }
  EXPECT_EQ(detail::provenance_json(one), detail::provenance_json(two));
}

TEST_F(Combined, TracesOfSeveralSeedsRecordNoSingleSeed) {
  trace_all(5, /*seeds_differ=*/true);
  const nlohmann::json p = detail::provenance_json(*combine(scene_fluxes()).provenance);
  EXPECT_TRUE(p["options"]["seed"].is_null());
  EXPECT_EQ(p["options"]["photons"], kPhotons);
  trace_all(7);
  EXPECT_EQ(detail::provenance_json(*combine(scene_fluxes()).provenance)["options"]["seed"], 7u);
}

}  // namespace
}  // namespace lightsolver::test
