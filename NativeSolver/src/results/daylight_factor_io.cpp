// The results' daylight-factor object, both ways.
#include "results/daylight_factor_io.hpp"

#include <cstdio>
#include <string>

namespace lightsolver::detail {
namespace {

void put(nlohmann::json& j, const std::string& prefix, const OrderStatistic& o) {
  j[prefix + "_percent"] = o.value;
  j[prefix + "_ci_low_percent"] = o.low;
  j[prefix + "_ci_high_percent"] = o.high;
}

OrderStatistic get(const JsonNode& n, const std::string& prefix) {
  return {n.at((prefix + "_percent").c_str()).number(),
          n.at((prefix + "_ci_low_percent").c_str()).number(),
          n.at((prefix + "_ci_high_percent").c_str()).number()};
}

Estimate estimate(const JsonNode& n, const char* mean_key) {
  Estimate e;
  e.mean = n.at(mean_key).number();
  e.ci_low = n.at("ci_low_percent").number();
  e.ci_high = n.at("ci_high_percent").number();
  return e;
}

}  // namespace

nlohmann::json daylight_factor_json(const DaylightFactorResult& d) {
  nlohmann::json j = {{"sky", d.sky},
                      {"outside_illuminance_lx", d.outside_illuminance_lx},
                      {"mean_percent", d.mean.mean},
                      {"ci_low_percent", d.mean.ci_low},
                      {"ci_high_percent", d.mean.ci_high}};
  put(j, "min", d.min);
  put(j, "p50", d.p50);
  put(j, "p95", d.p95);
  nlohmann::json cells = nlohmann::json::array();
  for (const Estimate& c : d.cells) {
    cells.push_back(
        {{"percent", c.mean}, {"ci_low_percent", c.ci_low}, {"ci_high_percent", c.ci_high}});
  }
  j["cells"] = std::move(cells);
  return j;
}

std::string daylight_factor_line(const std::string& target, const DaylightFactorResult& d) {
  const auto show = [](double v, double low, double high) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "%.3f %% [%.3f, %.3f]", v, low, high);
    return std::string(buf);
  };
  char out[64];
  std::snprintf(out, sizeof out, "%.0f lx", d.outside_illuminance_lx);
  return "daylight factor of " + target + " (sky \"" + d.sky + "\", outside " + out + "): mean " +
         show(d.mean.mean, d.mean.ci_low, d.mean.ci_high) + ", over 50 % of the area " +
         show(d.p50.value, d.p50.low, d.p50.high) + ", over 95 % " +
         show(d.p95.value, d.p95.low, d.p95.high) + ", min " +
         show(d.min.value, d.min.low, d.min.high) + "\n";
}

DaylightFactorResult read_daylight_factor(const JsonNode& n) {
  DaylightFactorResult d;
  d.sky = n.at("sky").string();
  d.outside_illuminance_lx = n.at("outside_illuminance_lx").number();
  d.mean = estimate(n, "mean_percent");
  d.min = get(n, "min");
  d.p50 = get(n, "p50");
  d.p95 = get(n, "p95");
  const JsonNode cells = n.at("cells");
  for (std::size_t k = 0; k < cells.array_size(); ++k) {
    d.cells.push_back(estimate(cells[k], "percent"));
  }
  return d;
}

}  // namespace lightsolver::detail
