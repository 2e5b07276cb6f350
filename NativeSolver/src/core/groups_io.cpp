#include "core/groups_io.hpp"

namespace lightsolver::detail {
namespace {

nlohmann::json tally_fields(const Tally& t) { return {{"sum", t.sum}, {"sum_sq", t.sum_sq}}; }

}  // namespace

void add_groups_json(const Results& r, nlohmann::json& j) {
  nlohmann::json groups = nlohmann::json::array();
  for (const GroupResult& g : r.groups) {
    groups.push_back({{"name", g.name},
                      {"flux_lm", g.flux_lm},
                      {"photons", g.photons},
                      {"luminaires", g.luminaires}});
  }
  j["groups"] = std::move(groups);
  nlohmann::json luminaires = nlohmann::json::array();
  for (const LuminaireResult& l : r.luminaires) {
    luminaires.push_back({{"name", l.name},
                          {"type", l.type},
                          {"group", l.group},
                          {"flux_lm", l.flux_lm},
                          {"tilt_factor", l.tilt_factor},
                          {"dimming", l.dimming},
                          {"emitted_flux_lm", l.emitted_flux_lm}});
  }
  j["luminaires"] = std::move(luminaires);
  if (!r.rescaled.empty()) {
    nlohmann::json factors = nlohmann::json::object();
    for (const auto& [name, factor] : r.rescaled) factors[name] = factor;
    j["rescaled"] = std::move(factors);
  }
}

void add_contributions_json(const TargetResult& t, nlohmann::json& j) {
  if (t.contributions.empty()) return;
  nlohmann::json all = nlohmann::json::object();
  for (const Contribution& c : t.contributions) {
    nlohmann::json one = {{"illuminance_lux", c.estimate.mean},
                          {"ci_low_lux", c.estimate.ci_low},
                          {"ci_high_lux", c.estimate.ci_high},
                          {"hits", c.estimate.hits}};
    if (t.observer_grid) {  // the maximum's point, and every point's [sum, sum_sq]
      one.update(tally_fields(c.tallies.at(t.observer_grid->max_at.value_or(0))));
      nlohmann::json points = nlohmann::json::array();
      for (const Tally& p : c.tallies) points.push_back({p.sum, p.sum_sq});
      one["points"] = std::move(points);
    } else {
      one.update(tally_fields(c.tallies.at(0)));
    }
    if (t.is_grid) {
      nlohmann::json cells = nlohmann::json::array();
      for (std::size_t k = 0; k < c.cells.size(); ++k) {
        const Estimate& e = c.cells[k];
        nlohmann::json cell = {{"lux", e.mean},
                               {"ci_low_lux", e.ci_low},
                               {"ci_high_lux", e.ci_high},
                               {"hits", e.hits}};
        cell.update(tally_fields(c.tallies.at(1 + k)));
        cells.push_back(std::move(cell));
      }
      one["cells"] = std::move(cells);
    }
    all[c.group] = std::move(one);
  }
  j["contributions"] = std::move(all);
}

}  // namespace lightsolver::detail
