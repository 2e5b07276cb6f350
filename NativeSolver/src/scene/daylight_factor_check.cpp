// Daylight-factor grids: the sky they read and the checks of their keys.
#include "scene/daylight_factor_check.hpp"

#include <sstream>
#include <string>
#include <vector>

#include "daylight/sky_sampler.hpp"
#include "lightsolver/error.hpp"

namespace lightsolver::detail {
namespace {

std::string show(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

std::vector<std::size_t> skies(const Scene& s) {
  std::vector<std::size_t> out;
  for (std::size_t j = 0; j < s.luminaires.size(); ++j) {
    if (s.luminaires[j].type == Luminaire::Type::Sky) out.push_back(j);
  }
  return out;
}

constexpr const char* kDaylightKeys =
    "a daylight-factor grid takes df_target_percent, df_minimum_percent, or en17037 with "
    "median_diffuse_lx";

class Checks {
 public:
  Checks(const Scene& s, std::size_t i) : s_(s), i_(i), t_(s.targets[i]) {}

  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw InputError(s_.source_file, "targets[" + std::to_string(i_) + "]." + key, what);
  }

  // No DF key on a target that is not a daylight-factor grid.
  void not_daylight() const {
    const Requirements& r = t_.requirements;
    const char* why =
        "applies to a daylight-factor grid only (a grid with \"quantity\": \"daylight_factor\")";
    if (r.df_target_percent) fail("requirements.df_target_percent", why);
    if (r.df_minimum_percent) fail("requirements.df_minimum_percent", why);
    if (r.en17037 != En17037Level::None) fail("requirements.en17037", why);
    if (r.median_diffuse_lx) fail("requirements.median_diffuse_lx", why);
  }

  void requirements() const {
    const Requirements& r = t_.requirements;
    if (!r.task.empty()) {
      fail("task", std::string("an illuminance task does not apply to a daylight-factor grid: ") +
                       kDaylightKeys);
    }
    for (const auto& [key, v] :
         {std::pair{"em_lux", r.em_lux}, std::pair{"u0", r.u0}, std::pair{"emin_lux", r.emin_lux},
          std::pair{"ud", r.ud}, std::pair{"ugr_max", r.ugr_max}}) {
      if (v) {
        fail(std::string("requirements.") + key,
             std::string("an illuminance requirement does not apply to a daylight-factor "
                         "grid: ") +
                 kDaylightKeys);
      }
    }
    for (const auto& [key, v] : {std::pair{"df_target_percent", r.df_target_percent},
                                 std::pair{"df_minimum_percent", r.df_minimum_percent}}) {
      if (v && !(*v > 0.0 && *v <= 100.0)) {
        fail(std::string("requirements.") + key,
             "must be > 0 and at most 100 % (got " + show(*v) + ")");
      }
    }
    if (r.median_diffuse_lx && r.en17037 == En17037Level::None) {
      fail("requirements.median_diffuse_lx",
           "is used only with en17037 (\"minimum\", \"medium\" or \"high\"): it turns the "
           "level's illuminances into daylight factors");
    }
    if (r.en17037 != En17037Level::None && !r.median_diffuse_lx) {
      fail("requirements.median_diffuse_lx",
           "EN 17037's daylight-factor targets need the site's median external diffuse "
           "illuminance E_v,d,med in lx (`lightsolver weather FILE.epw` gives it)");
    }
    if (r.median_diffuse_lx &&
        !(*r.median_diffuse_lx > 0.0 && *r.median_diffuse_lx <= limits::kMaxIlluminance_lx)) {
      fail("requirements.median_diffuse_lx",
           "must be > 0 and at most 10^7 lx (got " + show(*r.median_diffuse_lx) + ")");
    }
  }

  // Exactly one sky, alone in its group, with light outside.
  void sky() const {
    const std::vector<std::size_t> found = skies(s_);
    if (found.empty()) {
      fail("quantity",
           "a daylight-factor grid needs a sky luminaire (type \"sky\"): the scene has none");
    }
    if (found.size() > 1) {
      fail("quantity",
           "a daylight-factor grid needs exactly one sky luminaire (the ratio is to "
           "its outside illuminance): the scene has " +
               std::to_string(found.size()) + " (luminaires[" + std::to_string(found[0]) +
               "] and luminaires[" + std::to_string(found[1]) + "])");
    }
    const Luminaire& sky = s_.luminaires[found[0]];
    for (std::size_t j = 0; j < s_.luminaires.size(); ++j) {
      if (j == found[0] || s_.luminaires[j].group_name() != sky.group_name()) continue;
      throw InputError(s_.source_file, "luminaires[" + std::to_string(j) + "].group",
                       "shares the group \"" + sky.group_name() + "\" with the sky (luminaires[" +
                           std::to_string(found[0]) + "]) whose daylight factor targets[" +
                           std::to_string(i_) +
                           "] reports: the sky's group must hold the sky alone");
    }
    if (sky.sky_emitter && !(sky.sky_emitter->sky().diffuse_horizontal_lx() > 0.0)) {
      fail("quantity", "the sky gives no outside illuminance: no daylight factor");
    }
  }

 private:
  const Scene& s_;
  std::size_t i_;
  const Target& t_;
};

}  // namespace


void check_daylight_factor(const Scene& s, std::size_t i) {
  const Checks c(s, i);
  const Target& t = s.targets[i];
  if (t.quantity != Target::Quantity::DaylightFactor) {
    c.not_daylight();
    return;
  }
  if (t.type != Target::Type::Grid) c.fail("quantity", "only a grid reports a daylight factor");
  c.requirements();
  c.sky();
}

}  // namespace lightsolver::detail
