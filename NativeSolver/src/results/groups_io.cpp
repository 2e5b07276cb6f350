#include "results/groups_io.hpp"

#include <cmath>
#include <string>

namespace lightsolver::detail {
namespace {

nlohmann::json tally_fields(const Tally& t) { return {{"sum", t.sum}, {"sum_sq", t.sum_sq}}; }

nlohmann::json direct_json(const DirectLight& d) {
  return {{"lux", d.lux}, {"variance_lx2", d.variance_lx2}, {"lit", d.lit}};
}

DirectLight read_direct(const JsonNode& n) {
  DirectLight d{n.at("lux").number(), n.at("variance_lx2").number(),
                n.at("lit").unsigned_integer()};
  if (!(std::isfinite(d.lux) && d.lux >= 0.0)) n.at("lux").fail("expected a finite number >= 0");
  if (!(std::isfinite(d.variance_lx2) && d.variance_lx2 >= 0.0)) {
    n.at("variance_lx2").fail("expected a finite number >= 0");
  }
  return d;
}

// A contribution's `photon_light`: absent for a group whose photons tallied all its light.
const char* photon_light_name(Contribution::PhotonLight p) {
  return p == Contribution::PhotonLight::Reflected ? "reflected" : "none";
}

Contribution::PhotonLight read_photon_light(const JsonNode& c) {
  if (!c.has("photon_light")) return Contribution::PhotonLight::All;
  const JsonNode n = c.at("photon_light");
  const std::string v = n.string();
  if (v == "reflected") return Contribution::PhotonLight::Reflected;
  if (v == "none") return Contribution::PhotonLight::None;
  n.fail("expected \"reflected\" or \"none\"");
}

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
    if (c.photon_light != Contribution::PhotonLight::All) {  // next-event estimation
      one["photon_light"] = photon_light_name(c.photon_light);
      if (!c.direct.empty()) one["direct"] = direct_json(c.direct.at(0));
    }
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
        if (!c.direct.empty()) cell["direct"] = direct_json(c.direct.at(1 + k));
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
    part.photon_light = read_photon_light(c);
    // A next-event group's direct parts: the whole target's, then each cell's (none at eyes).
    const bool direct = c.has("direct");
    if (direct && part.photon_light == Contribution::PhotonLight::All) {
      c.at("direct").fail("a direct part needs photon_light \"reflected\" or \"none\"");
    }
    if (direct) part.direct.push_back(read_direct(c.at("direct")));
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
        if (direct) part.direct.push_back(read_direct(cells[k].at("direct")));
        if (!direct && cells[k].has("direct")) {
          cells[k].at("direct").fail("a cell's direct part without the target's");
        }
      }
    }
    out.push_back(std::move(part));
  }
  return out;
}

}  // namespace lightsolver::detail
