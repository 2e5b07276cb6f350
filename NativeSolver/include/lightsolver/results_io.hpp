#pragma once
/// \file results_io.hpp
/// Results JSON read back: the inverse of results_to_json() (solver.hpp).
#include <string>

#include "lightsolver/solver.hpp"

namespace lightsolver {

/// The inverse of results_to_json(): results JSON text (format `lightsolver.results/1`) read
/// back, so that results_to_json(results_from_json(text)) == text for any text it wrote (fields
/// it does not write stay at their defaults: a group part's sigma, an observer's luminaire sum
/// and its luminaires' geometry). Throws InputError naming `source` and the field for text
/// that is no such document.
Results results_from_json(const std::string& text, const std::string& source = "");

}  // namespace lightsolver
