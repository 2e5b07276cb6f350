#include "results/effects_io.hpp"

#include <algorithm>

namespace lightsolver::detail {

nlohmann::json effects_json(const EffectsReport& effects) {
  nlohmann::json skipped = nlohmann::json::array();
  for (const SkippedEffect& s : effects.skipped) {
    skipped.push_back({{"effect", s.effect}, {"reason", s.reason}});
  }
  nlohmann::json out = {{"simulated", effects.simulated}, {"skipped", std::move(skipped)}};
  // Only where a simulated effect was not applied everywhere (next_event_direct under auto).
  for (const EffectNote& n : effects.notes) {
    out["notes"].push_back({{"effect", n.effect}, {"note", n.note}});
  }
  return out;
}

namespace {

std::string words(std::string name) {
  std::replace(name.begin(), name.end(), '_', ' ');
  return name;
}

}  // namespace

std::string effects_lines(const EffectsReport& effects, bool list_skipped) {
  std::string out = "simulated:";
  for (std::size_t i = 0; i < effects.simulated.size(); ++i) {
    out += (i == 0 ? " " : ", ") + words(effects.simulated[i]);
  }
  if (effects.simulated.empty()) out += " nothing";
  // Skipped effects are what the scene does not need (a type it has none of): one count, not
  // a line each, unless asked for.
  if (!effects.skipped.empty() && !list_skipped) {
    out += " (" + std::to_string(effects.skipped.size()) +
           " effects not needed by this scene, not simulated: --effects lists them)";
  }
  out += "\n";
  for (const EffectNote& n : effects.notes) out += words(n.effect) + ": " + n.note + "\n";
  if (!list_skipped) return out;
  for (const SkippedEffect& s : effects.skipped) {
    out += s.reason + ": " + words(s.effect) + " not simulated\n";
  }
  return out;
}

}  // namespace lightsolver::detail
