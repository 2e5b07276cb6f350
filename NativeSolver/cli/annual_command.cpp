// `lightsolver annual SCENE --weather FILE.epw [--out-dir DIR]`: the scene's year of daylight
// (lightsolver/annual_run.hpp): a summary on stdout; annual.json (the metrics) and annual.npz
// (every hour of every grid, deflated) written whole into DIR, created only once they exist.
#include "annual_command.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>

#include "lightsolver/annual_run.hpp"
#include "lightsolver/error.hpp"
#include "lightsolver/output_file.hpp"
#include "lightsolver/scene_io.hpp"
#include "npz_writer.hpp"
#include "processes.hpp"

namespace lightsolver::cli {

namespace {

struct AnnualArgs {
  std::string scene, out_dir;
  AnnualRunOptions options;
  std::uint64_t seed = 0;
  std::uint64_t max_photons = 0;
  std::string occupied, occupancy_file;
  double blinds = 0.0;
};

// Arrays per grid i: g<i>_mean, g<i>_low, g<i>_high (hours × cells, lx, float32; the hour's
// interval at the run's confidence) and g<i>_direct_sun (with a sun); month_day_hour.
std::string npz(const AnnualResult& r) {
  NpzWriter z(true);
  const std::size_t hours = r.month_day_hour.size() / 3;
  z.add("month_day_hour", "<i4", r.month_day_hour, {hours, 3});
  for (std::size_t i = 0; i < r.grids.size(); ++i) {
    const AnnualGrid& g = r.grids[i];
    const std::string p = "g" + std::to_string(i) + "_";
    const std::vector<std::size_t> shape{hours, static_cast<std::size_t>(g.hourly.cells)};
    z.add(p + "mean", "<f4", g.hourly.mean, shape);
    z.add(p + "low", "<f4", g.low, shape);
    z.add(p + "high", "<f4", g.high, shape);
    if (!g.direct_sun.empty()) z.add(p + "direct_sun", "<f4", g.direct_sun, shape);
  }
  return z.finish();
}

// "9-18": the EPW hour stamps of the day's first and last occupied hours.
void occupied_hours(const std::string& text, AnnualRunOptions& o) {
  int first = 0, last = 0;
  char dash = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d %c %d %c", &first, &dash, &last, &extra) != 3 || dash != '-' ||
      first < 1 || last > 24 || first > last) {
    throw InputError(
        "", "--occupied-hours",
        "give FIRST-LAST EPW hour stamps, 1 <= FIRST <= LAST <= 24 (got \"" + text + "\")");
  }
  o.occupied_first = first;
  o.occupied_last = last;
}

// One 0 or 1 per line (blank lines and # comments skipped).
std::vector<std::uint8_t> occupancy_values(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "", "cannot read the occupancy file");
  std::vector<std::uint8_t> v;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    const auto b = line.find_first_not_of(" \t\r");
    if (b == std::string::npos || line[b] == '#') continue;
    const auto e = line.find_last_not_of(" \t\r");
    const std::string value = line.substr(b, e - b + 1);
    if (value != "0" && value != "1") {
      throw InputError(path, "line " + std::to_string(n), "must be 0 or 1, got \"" + value + "\"");
    }
    v.push_back(value == "1" ? 1 : 0);
  }
  return v;
}

std::string interval(const nlohmann::json& m, double scale, const char* unit) {
  char b[96];
  std::snprintf(b, sizeof b, "%.1f%s [%.1f, %.1f]", scale * m["estimate"].get<double>(), unit,
                scale * m["low"].get<double>(), scale * m["high"].get<double>());
  return b;
}

void print_summary(const nlohmann::json& s) {
  const auto& w = s["weather"];
  std::printf("weather    %s (%s), %d hours, %d with a sky\n",
              w["location"].get<std::string>().c_str(), w["file"].get<std::string>().c_str(),
              w["hours"].get<int>(), w["sky_hours"].get<int>());
  const auto& t = s["trace"];
  std::printf(
      "trace      %llu photons on %s: %d sky patch groups, coefficients and direct sun "
      "%.1f MB, %s\n",
      static_cast<unsigned long long>(t["photons"].get<std::uint64_t>()),
      t["backend"].get<std::string>().c_str(), t["sky_patch_groups"].get<int>(),
      t["coefficient_bytes"].get<double>() / 1e6, t["stop_reason"].get<std::string>().c_str());
  const auto& sec = s["seconds"];
  std::printf(
      "time       sky matrix %.2f s, trace %.2f s, hours and metrics %.2f s, total %.2f s\n",
      sec["sky_matrix"].get<double>(), sec["trace"].get<double>(),
      sec["hours_and_metrics"].get<double>(), sec["total"].get<double>());
  for (const auto& g : s["grids"]) {
    const auto& m = g["metrics"];
    std::printf(
        "grid       %s (%d cells): sDA300/50%% %s (%s), ASE1000,250h %s, mean DA300 %s, "
        "UDI 100-2000 %s\n",
        g["name"].get<std::string>().c_str(), g["cells"].get<int>(),
        interval(m["sda_percent"], 1.0, " %").c_str(),
        m["sda_nominal_verdict"].get<std::string>().c_str(),
        m["ase_percent"].is_null()
            ? "-"
            : (std::to_string(m["ase_percent"].get<double>()).substr(0, 5) + " %").c_str(),
        interval(m["da_fraction"], 100.0, " %").c_str(),
        interval(m["udi_useful_fraction"], 100.0, " %").c_str());
  }
}

int run_annual_command(AnnualArgs& a) {
  try {
    if (a.seed > 0) a.options.seed = a.seed;
    if (a.blinds > 0.0) a.options.blinds_transmittance = a.blinds;
    if (a.max_photons > 0) a.options.max_photons = a.max_photons;
    if (!a.occupied.empty()) occupied_hours(a.occupied, a.options);
    if (!a.occupancy_file.empty()) a.options.occupancy = occupancy_values(a.occupancy_file);
    const Scene scene = load_scene(a.scene);
    a.options.processes = processes();  // under mpirun: every rank traces, rank 0 writes
    const AnnualResult r = run_annual(scene, a.options);
    if (!reports()) return 0;
    print_summary(r.summary);
    if (!a.out_dir.empty()) {
      const std::string json = r.summary.dump(1) + "\n", arrays = npz(r);
      std::filesystem::create_directories(a.out_dir);
      write_file_atomically((std::filesystem::path(a.out_dir) / "annual.npz").string(), arrays);
      write_file_atomically((std::filesystem::path(a.out_dir) / "annual.json").string(), json);
      std::printf("written    %s/annual.json, annual.npz\n", a.out_dir.c_str());
    }
    return 0;
  } catch (const std::exception& e) {  // InputError too: the message names file and field
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace

void add_annual_command(CLI::App& app) {
  auto a = std::make_shared<AnnualArgs>();
  CLI::App* cmd = app.add_subcommand(
      "annual",
      "A year of daylight by daylight coefficients: sky patches and the year's suns traced once, "
      "every hour rebuilt with its interval, annual metrics (DA, sDA, ASE, UDI, EN 17037)");
  cmd->add_option("scene", a->scene, "Scene file (its sky's openings, grids, meshes)")->required();
  cmd->add_option("--weather", a->options.weather, "EnergyPlus weather file (.epw)")->required();
  cmd->add_option("--mf", a->options.sky.mf,
                  "Reinhart subdivision (1: 145 patches, 2: 577, 4: 2305)")
      ->capture_default_str();
  cmd->add_option("--north-deg", a->options.sky.north_deg,
                  "True north from +y, counter-clockwise seen from above")
      ->capture_default_str();
  cmd->add_option("--ground-reflectance", a->options.ground_reflectance,
                  "The ground's ρ (default: the scene's sky's ground_reflectance)");
  cmd->add_flag("--illuminance", a->options.sky.use_illuminance,
                "The Perez sky from the illuminance columns (default: irradiance with Perez' "
                "efficacies, as gendaymtx)");
  cmd->add_option("--photons", a->options.photons, "Photons of the one trace, all groups")
      ->capture_default_str();
  cmd->add_option("--seed", a->seed, "Random seed (default: the scene's)");
  cmd->add_option("--backend", a->options.backend, "auto, embree or vulkan")->capture_default_str();
  cmd->add_option("--threads", a->options.threads, "CPU threads (0: all)")->capture_default_str();
  cmd->add_option("--confidence", a->options.confidence, "Of every interval")
      ->capture_default_str();
  cmd->add_option("--blinds-transmittance", a->blinds,
                  "LM-83's blinds rule: blinds-closed hours get the sky's light times this");
  cmd->add_option("--occupied-hours", a->occupied,
                  "Occupied every day from the EPW hour stamp FIRST to LAST, as FIRST-LAST "
                  "(default 9-18: IES LM-83's 8:00-18:00)");
  cmd->add_option("--occupancy", a->occupancy_file,
                  "A file of one 0 or 1 per hour of the weather file (the occupied hours)");
  cmd->add_flag("--decide", a->options.decide,
                "Trace on (twice the photons per look) until every sDA and EN 17037 verdict is "
                "decided, within --max-photons");
  cmd->add_option("--max-photons", a->max_photons, "--decide's budget (default 16 x --photons)");
  cmd->add_option("--out-dir", a->out_dir, "Write annual.json and annual.npz into this folder");
  cmd->callback([a] {
    if (const int rc = run_annual_command(*a); rc != 0) throw CLI::RuntimeError(rc);
  });
}

}  // namespace lightsolver::cli
