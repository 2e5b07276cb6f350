#pragma once
// The results' provenance (lightsolver/provenance.hpp) inside the library: hashing a scene's
// canonical content and the files it reads, filling a run's record, and its JSON both ways.
#include <chrono>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

#include "io/json_reader.hpp"
#include "lightsolver/provenance.hpp"
#include "lightsolver/solver.hpp"

namespace lightsolver::detail {

/// SHA-256 of `bytes`, lowercase hex (OpenSSL's libcrypto).
std::string sha256_hex(std::string_view bytes);

/// SHA-256 of a file's bytes; nullopt when it cannot be opened or read.
std::optional<std::string> file_sha256(const std::string& path);

/// The canonical text of a JSON document, what scene_sha256 hashes: compact (no whitespace),
/// object keys sorted by their UTF-8 bytes, numbers as nlohmann/json writes them (the shortest
/// text that reads back as the same double) except that a number with an integral value below
/// 2^53 in magnitude is written as an integer (1.0, 1e0 and 1 are the same value; -0 is 0).
/// Re-indenting or reordering keys leaves it unchanged; any value change changes it.
std::string canonical_json(const nlohmann::json& doc);

// sha256_hex(canonical_json(doc)), computed without building the text.
std::string canonical_sha256(const nlohmann::json& doc);

/// The source of a parsed scene document: the hash of its canonical text and the files it reads
/// (every string "file" of its meshes, luminaires and targets, resolved against `base_dir` as
/// the loader resolves them, and the requirements table when a target names a task). With
/// `strict` a file that cannot be read is an InputError naming it and `scene_file`; otherwise
/// it is listed with sha256 "".
SceneSource scene_source(const nlohmann::json& doc, const std::string& base_dir,
                         const std::string& scene_file, bool strict);

/// What a run records: the scene's source, the build, the backend and its device, the
/// processes and threads, every resolved option (from the results `r` the run filled and the
/// scene's settings), the run's start and end, the host and `options.command`.
Provenance run_provenance(const Scene& scene, const SolveOptions& options, const Results& r,
                          int threads, const std::string& device,
                          std::chrono::system_clock::time_point started,
                          std::chrono::system_clock::time_point finished);

/// This machine's host name ("unknown" when it has none).
std::string host_name();

/// "2025-01-31T09:30:00Z".
std::string utc_text(std::chrono::system_clock::time_point t);

/// The results JSON's "provenance" object, and its inverse (InputError naming the field).
nlohmann::json provenance_json(const Provenance& p);
Provenance read_provenance(const JsonNode& n);

/// The source commit the build was made from (generated at build time: source_commit.cmake).
const char* source_commit();

}  // namespace lightsolver::detail
