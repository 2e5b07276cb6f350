#pragma once
// The scene's and the results' `sunlight_exposure` objects (lightsolver/sunlight.hpp) through
// the JSON reader, so their errors name the file and the field as every other key's do.
#include "io/json_reader.hpp"
#include "lightsolver/sunlight.hpp"

namespace lightsolver::detail {

/// The scene's `sunlight_exposure` (`n`), validated; `north_deg` is the scene's
/// `metadata.north_deg` (0 without one). A date outside 1 February … 21 March adds a warning.
SunlightExposureSpec read_sunlight_exposure(const JsonNode& n, double north_deg,
                                            Warnings& warnings);

/// The results' `sunlight_exposure` (`n`): the inverse of sunlight_exposure_json().
SunlightExposureResult read_sunlight_exposure_result(const JsonNode& n);

}  // namespace lightsolver::detail
