#pragma once
// A fast path for parse_json_text (json_reader.cpp): strict JSON with plain numbers parsed by
// std::from_chars into the same nlohmann document nlohmann's own parser builds. Anything it does
// not take on itself (an error of any kind, a byte-order mark, nesting over 256 levels, a number
// from_chars cannot represent) gives nullopt, and nlohmann's parser then reads the text and
// words its errors: results and messages stay nlohmann's; only the time changes (scenes with
// large inline meshes are mostly numbers, which nlohmann's lexer reads ~3x slower).
#include <nlohmann/json.hpp>
#include <optional>
#include <string_view>

namespace lightsolver::detail {

std::optional<nlohmann::json> parse_json_fast(std::string_view text);

}  // namespace lightsolver::detail
