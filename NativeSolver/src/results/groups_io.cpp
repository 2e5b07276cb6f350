#include "results/groups_io.hpp"

#include <string>

namespace lightsolver::detail {
namespace {

nlohmann::json tally_fields(const Tally& t) { return {{"sum", t.sum}, {"sum_sq", t.sum_sq}}; }

std::vector<std::string> strings(const JsonNode& n) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < n.array_size(); ++i) out.push_back(n[i].string());
  return out;
}

Tally read_tally(const JsonNode& n) {
  return {n.at("sum").unsigned_integer(), n.at("sum_sq").unsigned_integer()};
}

// A part's or a cell's estimate: {mean_key, "ci_low_lux", "ci_high_lux", "hits"}.
Estimate read_estimate(const JsonNode& n, const char* mean_key) {
  Estimate e;
  e.mean = n.at(mean_key).number();
  e.ci_low = n.at("ci_low_lux").number();
  e.ci_high = n.at("ci_high_lux").number();
  e.hits = n.at("hits").unsigned_integer();
  return e;
}

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

void read_groups_json(const JsonNode& root, Results& r) {
  if (!root.has("groups")) return;
  const JsonNode groups = root.at("groups");
  for (std::size_t i = 0; i < groups.array_size(); ++i) {
    const JsonNode g = groups[i];
    r.groups.push_back({g.at("name").string(), g.at("flux_lm").number(),
                        g.at("photons").unsigned_integer(), strings(g.at("luminaires"))});
  }
  if (root.has("luminaires")) {
    const JsonNode list = root.at("luminaires");
    for (std::size_t i = 0; i < list.array_size(); ++i) {
      const JsonNode l = list[i];
      r.luminaires.push_back({l.at("name").string(), l.at("type").string(), l.at("group").string(),
                              l.at("flux_lm").number(), l.at("tilt_factor").number(),
                              l.at("dimming").number(), l.at("emitted_flux_lm").number()});
    }
  }
  if (root.has("rescaled")) {  // in group order (the JSON keys them by name)
    const JsonNode factors = root.at("rescaled");
    for (const GroupResult& g : r.groups) {
      r.rescaled.emplace_back(g.name, factors.at(g.name.c_str()).number());
    }
    if (r.rescaled.size() != factors.object().size()) factors.fail("names an unknown group");
  }
}

std::vector<Contribution> read_contributions_json(const JsonNode& n, const TargetResult& t,
                                                  const std::vector<GroupResult>& groups) {
  std::vector<Contribution> out;
  const JsonNode all = n.at("contributions");
  if (all.object().size() != groups.size()) all.fail("expected one entry per luminaire group");
  for (const GroupResult& g : groups) {
    const JsonNode c = all.at(g.name.c_str());
    Contribution part;
    part.group = g.name;
    part.estimate = read_estimate(c, "illuminance_lux");
    if (t.observer_grid) {
      const JsonNode list = c.at("points");
      for (std::size_t k = 0; k < list.array_size(); ++k) {
        if (list[k].array_size() != 2) list[k].fail("expected [sum, sum_sq]");
        part.tallies.push_back({list[k][0].unsigned_integer(), list[k][1].unsigned_integer()});
      }
    } else {
      part.tallies.push_back(read_tally(c));
    }
    if (t.is_grid) {
      const JsonNode cells = c.at("cells");
      for (std::size_t k = 0; k < cells.array_size(); ++k) {
        part.cells.push_back(read_estimate(cells[k], "lux"));
        part.tallies.push_back(read_tally(cells[k]));
      }
    }
    out.push_back(std::move(part));
  }
  return out;
}

}  // namespace lightsolver::detail
