#pragma once
// A daylight-factor grid's "daylight_factor" object in the results JSON, written by
// results_io.cpp and read back by results_from_json.cpp (a round trip gives the same text).
#include <nlohmann/json.hpp>
#include <string>

#include "io/json_reader.hpp"
#include "lightsolver/solver.hpp"

namespace lightsolver::detail {

/// {"sky", "outside_illuminance_lx", "mean_percent", "ci_low_percent", "ci_high_percent",
///  "min_percent", ..., "p50_percent", ..., "p95_percent", ..., "cells": [{"percent",
///  "ci_low_percent", "ci_high_percent"}]} (docs/scene-format.md, "Results").
nlohmann::json daylight_factor_json(const DaylightFactorResult& d);

/// The CLI table's line: "daylight factor of NAME (sky "S", outside 10000 lx): mean 3.17 %
/// [3.16, 3.17], over 50 % of the area 2.12 % [2.06, 2.18], over 95 % 1.19 % [...], min ...".
std::string daylight_factor_line(const std::string& target, const DaylightFactorResult& d);

/// The inverse of daylight_factor_json (sigma and hits, not written, stay 0).
DaylightFactorResult read_daylight_factor(const JsonNode& n);

}  // namespace lightsolver::detail
