#pragma once
// An observer grid's glare terms in the results JSON (`observer_grid.glare_terms`, written with
// contributions), both ways: results_to_json writes them, results_from_json reads them back for
// `rescale` (docs/glare.md, "Rescaling an observer grid"). Only the format lives here; glare
// (above core: docs/solver.md, "Layers") rates them.
#include <cstddef>
#include <nlohmann/json.hpp>

#include "io/json_reader.hpp"
#include "lightsolver/solver.hpp"

namespace lightsolver::detail {

/// The status characters of glare terms: 'c' counted, the geometric reasons 'b', 'l', 'o',
/// 'd' (glare_terms.hpp), 'x' never rated (not_rated says why).
inline constexpr const char* kGlareStatus = "cblodx";

/// `glare_terms`: luminaires, not_rated, one status string and one terms array per point.
nlohmann::json glare_terms_json(const GlareTerms& terms);

/// `glare_terms` read back for `points` points; InputError naming the field when any is
/// missing, short or out of range (unknown status, L or omega <= 0, p < 1).
GlareTerms read_glare_terms(const JsonNode& n, std::size_t points);

}  // namespace lightsolver::detail
