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

std::string effects_lines(const EffectsReport& effects) {
  std::string out;
  for (const SkippedEffect& s : effects.skipped) {
    std::string words = s.effect;
    std::replace(words.begin(), words.end(), '_', ' ');
    out += s.reason + ": " + words + " not simulated\n";
  }
  return out;
}

}  // namespace lightsolver::detail
