// `lightsolver sunlight SCENE [--out F.json] [--json]`: the same function as the run's
// `sunlight_exposure` and Python's lightsolver.sunlight_exposure (docs/daylight.md).
#include "sunlight_command.hpp"

#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "lightsolver/error.hpp"
#include "lightsolver/output_file.hpp"
#include "lightsolver/scene.hpp"
#include "lightsolver/sunlight.hpp"

namespace lightsolver::cli {
namespace {

struct SunlightArgs {
  std::string scene;
  std::string out;
  bool json = false;
};

int run_sunlight(const SunlightArgs& a) {
  try {
    // The output path is checked before the work, so a bad one costs nothing and writes nothing.
    if (!a.out.empty()) check_writable(a.out, "sunlight exposure file");
    const Scene scene = load_sunlight_scene(a.scene);
    const SunlightExposureResult r = sunlight_exposure(scene);
    const std::string text = sunlight_exposure_json(r).dump(2) + "\n";
    if (!a.out.empty()) write_file_atomically(a.out, text);
    for (const std::string& w : scene.warnings) std::cerr << "warning: " << w << "\n";
    std::cout << (a.json ? text : sunlight_exposure_table(r));
    return 0;
  } catch (const std::exception& e) {  // InputError too: the message names file and field
    std::cerr << "error: " << e.what() << "\n";
  }
  return 1;
}

}  // namespace

void add_sunlight_command(CLI::App& app) {
  auto a = std::make_shared<SunlightArgs>();
  CLI::App* cmd = app.add_subcommand(
      "sunlight",
      "EN 17037 sunlight exposure: the hours of possible sunlight at the scene's window "
      "reference points on its date (its `sunlight_exposure`), with the scene's obstructions");
  cmd->add_option("scene", a->scene, "Scene file (JSON)")->required();
  cmd->add_option("--out", a->out, "Also write the result here (JSON)");
  cmd->add_flag("--json", a->json, "Print the JSON object instead of the table");
  cmd->callback([a] {
    if (const int rc = run_sunlight(*a); rc != 0) throw CLI::RuntimeError(rc);
  });
}

}  // namespace lightsolver::cli
