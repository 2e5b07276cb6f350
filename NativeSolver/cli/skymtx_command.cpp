// `lightsolver skymtx FILE.epw [--mf N] [--out F.npz]`: the year's sky vectors, a summary on
// stdout (hours, memory, the annual horizontal illuminance against the file's), the arrays in
// an .npz (docs/daylight.md, "Sky patches and sky vectors").
#include "skymtx_command.hpp"

#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "lightsolver/error.hpp"
#include "lightsolver/output_file.hpp"
#include "lightsolver/sky_patches.hpp"
#include "lightsolver/weather.hpp"
#include "npz_writer.hpp"

namespace lightsolver::cli {

namespace {

struct SkymtxArgs {
  std::string file, out;
  SkyMatrixOptions options;
};

std::string npz(const SkyMatrix& m, const WeatherFile& w, const SkyPatches& p) {
  NpzWriter z;
  const auto h = static_cast<std::size_t>(m.hours), n = static_cast<std::size_t>(m.patch_count);
  z.add("sky", "<f4", m.sky, {h, n});
  z.add("sun_direction", "<f4", m.sun_direction, {h, 3});
  z.add("sun_direct_normal_lx", "<f4", m.sun_direct_normal_lx, {h});
  z.add("sun_altitude_deg", "<f4", m.sun_altitude_deg, {h});
  z.add("diffuse_horizontal_lx", "<f4", m.diffuse_horizontal_lx, {h});
  z.add("status", "|u1", m.status, {h});
  std::vector<std::int32_t> stamp;  // month, day, hour per row
  for (const WeatherHour& x : w.hours) stamp.insert(stamp.end(), {x.month, x.day, x.hour});
  z.add("month_day_hour", "<i4", stamp, {h, 3});
  std::vector<double> centre, omega, mean_cos;
  for (const SkyPatch& q : p.patches()) {
    centre.insert(centre.end(), {q.centre.x, q.centre.y, q.centre.z});
    omega.push_back(q.solid_angle_sr);
    mean_cos.push_back(q.mean_cos_zenith);
  }
  z.add("patch_centre", "<f8", centre, {n, 3});
  z.add("patch_solid_angle_sr", "<f8", omega, {n});
  z.add("patch_mean_cos_zenith", "<f8", mean_cos, {n});
  const std::vector<double> meta{static_cast<double>(m.mf), p.north_deg(), m.max_quadrature_error};
  z.add("mf_north_deg_quadrature_error", "<f8", meta, {3});
  return z.finish();
}

int run_skymtx(const SkymtxArgs& a) {
  try {
    const WeatherFile w = read_epw(a.file);
    const auto t0 = std::chrono::steady_clock::now();
    const SkyMatrix m = sky_matrix(w, a.options);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const SkyPatches p(a.options.mf, a.options.north_deg);
    int sky_hours = 0;
    double rebuilt = 0.0, file = 0.0;
    const auto n = static_cast<std::size_t>(m.patch_count);
    for (std::size_t i = 0; i < static_cast<std::size_t>(m.hours); ++i) {
      sky_hours += m.status[i] == 2;
      file += w.hours[i].global_horizontal_lx.value_or(0.0);
      for (std::size_t k = 1; k < n; ++k)
        rebuilt += m.sky[i * n + k] * p.patch(static_cast<int>(k)).mean_cos_zenith;
      rebuilt += m.sun_direct_normal_lx[i] * m.sun_direction[i * 3 + 2];
    }
    std::printf("weather    %s (%s)\n", w.location.city.c_str(), a.file.c_str());
    std::printf("patches    %d (MF %d: ground, %d sky), north %.1f°\n", m.patch_count, m.mf,
                m.patch_count - 1, a.options.north_deg);
    std::printf("hours      %d, %d with a sky (sun above the horizon and diffuse light)\n", m.hours,
                sky_hours);
    std::printf("sun        %s\n", a.options.radiance_sun
                                       ? "in the 4 nearest patches (gendaymtx)"
                                       : "kept apart (sun_direction, sun_direct_normal_lx)");
    std::printf("memory     %.1f MB (float32, hours × patches, dense)\n", m.bytes() / 1e6);
    std::printf("time       %.2f s\n", s);
    std::printf(
        "annual global horizontal: from the sky vectors and sun %.4g lx·h, the file's "
        "%.4g lx·h (%+.2f %%)\n",
        rebuilt, file, file > 0 ? 100 * (rebuilt - file) / file : 0.0);
    if (!a.out.empty()) {
      write_file_atomically(a.out, npz(m, w, p));
      std::printf("written    %s\n", a.out.c_str());
    }
    return 0;
  } catch (const std::exception& e) {  // InputError too: the message names file and field
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace

void add_skymtx_command(CLI::App& app) {
  auto a = std::make_shared<SkymtxArgs>();
  CLI::App* cmd = app.add_subcommand(
      "skymtx",
      "A year of sky vectors from an EPW file (Reinhart patches, Perez skies; Radiance's "
      "gendaymtx analogue), optionally written as a numpy .npz");
  cmd->add_option("file", a->file, "EnergyPlus weather file (.epw)")->required();
  cmd->add_option("--mf", a->options.mf, "Reinhart subdivision (1: 145 patches, 2: 577, 4: 2305)")
      ->capture_default_str();
  cmd->add_option("--north-deg", a->options.north_deg,
                  "True north from +y, counter-clockwise seen from above")
      ->capture_default_str();
  cmd->add_option("--ground-reflectance", a->options.ground_reflectance, "The ground's ρ")
      ->capture_default_str();
  cmd->add_flag("--illuminance", a->options.use_illuminance,
                "The Perez sky from the illuminance columns (default: irradiance with Perez' "
                "efficacies, as gendaymtx)");
  cmd->add_flag("--radiance-sun", a->options.radiance_sun,
                "Put the sun into the 4 nearest patches as gendaymtx does");
  cmd->add_option("--out", a->out, "Write the arrays to this .npz file");
  cmd->callback([a] {
    if (const int rc = run_skymtx(*a); rc != 0) throw CLI::RuntimeError(rc);
  });
}

}  // namespace lightsolver::cli
