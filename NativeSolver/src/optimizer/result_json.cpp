#include <cmath>
#include <nlohmann/json.hpp>

#include "lightsolver/defaults.hpp"
#include "lightsolver/optimizer/result.hpp"

namespace lightsolver::optimizer {

namespace {

using json = nlohmann::ordered_json;  // keeps the documented key order

json estimate_json(const Estimate& e) {
  return {{"mean", e.mean},
          {"sigma", e.sigma},
          {"ci_low", e.ci_low},
          {"ci_high", e.ci_high},
          {"hits", e.hits}};
}

json interval_json(const Interval& i) {
  if (i.empty() || !std::isfinite(i.low) || !std::isfinite(i.high)) return nullptr;
  return json::array({i.low, i.high});
}

json member_json(const ResultMember& m) {
  json constraints = json::array();
  for (std::size_t i = 0; i < m.constraints.size(); ++i) {
    json c = estimate_json(m.constraints[i]);
    c["verdict"] = to_string(m.feasibility.at(i));
    constraints.push_back(std::move(c));
  }
  return {{"cells", m.cells},
          {"values", m.values},
          {"photons", m.photons},
          {"objective", estimate_json(m.objective)},
          {"constraints", std::move(constraints)}};
}

json counters_json(const Counters& c) {
  json cases = json::object();
  for (std::size_t i = 0; i < c.cases.size(); ++i)
    cases[std::string(paper_case(static_cast<UpdateCase>(i)))] = c.cases[i];
  return {{"iterations", c.iterations},
          {"evaluations", c.evaluations},
          {"cache_hits", c.cache_hits},
          {"photons", c.photons},
          {"photons_traced", c.photons_traced},
          {"screened_out", c.screened_out},
          {"confirmations", c.confirmations},
          {"infeasible", c.infeasible},
          {"refined", c.refined},
          {"refine_stage", c.refine_stage},
          {"refine_dropped", c.refine_dropped},
          {"inadmissible", c.inadmissible},
          {"cases", std::move(cases)},
          {"update_seconds", c.update_seconds},
          {"trace_seconds", c.trace_seconds},
          {"other_seconds", c.other_seconds},
          {"total_seconds", c.total_seconds}};
}

json iteration_json(const IterationStats& s) {
  return {{"iteration", s.iteration},
          {"start", s.start},
          {"k", s.k},
          {"update_seconds", s.update_seconds},
          {"trace_seconds", s.trace_seconds},
          {"other_seconds", s.other_seconds},
          {"evaluations", s.evaluations},
          {"photons", s.photons},
          {"total_photons", s.total_photons},
          {"isoc_size", s.isoc_size},
          {"siisoc", s.isoc_size ? interval_json(s.siisoc) : json(nullptr)},
          {"best", s.has_best ? estimate_json(s.best) : json(nullptr)}};
}

}  // namespace

std::string to_json(const OptimizationResult& r, int indent) {
  json isoc = json::array();
  for (const ResultMember& m : r.isoc) isoc.push_back(member_json(m));
  json history = json::array();
  for (const IterationStats& s : r.history) history.push_back(iteration_json(s));
  json j = {{"format", kOptimizationFormat},
            {"goal", r.goal == Goal::kMaximize ? "maximize" : "minimize"},
            {"confidence", r.confidence},
            {"stop", to_string(r.stop)},
            {"variables", r.variable_names},
            {"siisoc", r.isoc.empty() ? json(nullptr) : interval_json(r.siisoc)},
            {"isoc", std::move(isoc)},
            {"counters", counters_json(r.counters)},
            {"history", std::move(history)}};
  if (r.next_event) {
    j["next_event"] = {
        {"setting", r.next_event->setting},
        {"direct", r.next_event->direct},
        {"reason", r.next_event->direct ? json(nullptr) : json(r.next_event->reason)}};
  }
  return j.dump(indent);
}

}  // namespace lightsolver::optimizer
