#include "core/effects_io.hpp"

#include <algorithm>

namespace lightsolver::detail {

nlohmann::json effects_json(const EffectsReport& effects) {
  nlohmann::json skipped = nlohmann::json::array();
  for (const SkippedEffect& s : effects.skipped) {
    skipped.push_back({{"effect", s.effect}, {"reason", s.reason}});
  }
  return {{"simulated", effects.simulated}, {"skipped", std::move(skipped)}};
}

namespace {

std::string words(std::string name) {
  std::replace(name.begin(), name.end(), '_', ' ');
  return name;
}

}  // namespace

std::string effects_lines(const EffectsReport& effects) {
  std::string out = "simulated:";
  for (std::size_t i = 0; i < effects.simulated.size(); ++i) {
    out += (i == 0 ? " " : ", ") + words(effects.simulated[i]);
  }
  out += effects.simulated.empty() ? " nothing\n" : "\n";
  for (const SkippedEffect& s : effects.skipped) {
    out += s.reason + ": " + words(s.effect) + " not simulated\n";
  }
  return out;
}

}  // namespace lightsolver::detail
