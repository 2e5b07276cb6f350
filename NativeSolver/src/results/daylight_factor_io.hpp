#pragma once
// A daylight-factor grid's "daylight_factor" object in the results JSON, written by
// results_io.cpp and read back by results_from_json.cpp (a round trip gives the same text).
#include <nlohmann/json.hpp>

#include "io/json_reader.hpp"
#include "lightsolver/solver.hpp"

namespace lightsolver::detail {

/// {"sky", "outside_illuminance_lx", "mean_percent", "ci_low_percent", "ci_high_percent",
///  "min_percent", ..., "p50_percent", ..., "p95_percent", ..., "cells": [{"percent",
///  "ci_low_percent", "ci_high_percent"}]} (docs/scene-format.md, "Results").
nlohmann::json daylight_factor_json(const DaylightFactorResult& d);

/// The inverse of daylight_factor_json (sigma and hits, not written, stay 0).
DaylightFactorResult read_daylight_factor(const JsonNode& n);

}  // namespace lightsolver::detail
