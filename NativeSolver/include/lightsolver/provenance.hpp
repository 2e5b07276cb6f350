#pragma once
/// \file provenance.hpp
/// Where results come from (the results JSON's "provenance", docs/scene-format.md): the scene
/// content and every file it reads, by SHA-256, and the solver, build, machine, options and
/// time of the run. verify_provenance() says whether results belong to a scene file.

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace lightsolver {

/// One file a scene reads: a mesh, a photometric file, the requirements table.
struct SourceFile {
  /// As the scene writes it ("ies/panel.ies"); the requirements table (found by search, not
  /// named by the scene): its file name.
  std::string path;
  std::string kind;    ///< "mesh", "photometric", "requirements table", or "file"
  std::string sha256;  ///< of the file's bytes, lowercase hex; "" when it cannot be read
};

/// What a scene was read from: the SHA-256 of its canonical content (canonical_json()) and
/// the files it reads, in the order the scene names them, each once.
struct SceneSource {
  std::string sha256;
  std::vector<SourceFile> files;
};

/// A run option's value as the run resolved it (null: not set, e.g. no time limit).
using OptionValue = std::variant<std::monostate, bool, std::uint64_t, double, std::string>;

/// The results' provenance. The fields a run's processes and thread counts cannot change
/// (scene_sha256, files, solver_version, source_commit, build_type, backend, mpi_ranks,
/// options) are the same on every MPI rank; times, host, device and threads are rank 0's.
struct Provenance {
  /// The scene's content hash; absent for a scene built or changed in memory (no file content
  /// to compare with).
  std::optional<std::string> scene_sha256;
  std::vector<SourceFile> files;
  std::string solver_version;  ///< version()
  std::string source_commit;   ///< `git describe --always --dirty` at build time, or "unknown"
  std::string build_type;      ///< CMAKE_BUILD_TYPE ("Release", "Sanitize", ...)
  std::string backend;         ///< the backend that traced ("embree", "vulkan")
  std::string device;          ///< what it traced on, as the backend reports it
  int mpi_ranks = 1;           ///< processes that shared the run
  int threads = 0;             ///< worker threads of this process (0 resolved to the cores used)
  /// Every run option of the run options table (run_options.hpp) except threads and backend
  /// (fields of their own), by name, as the run resolved it, in table order.
  std::vector<std::pair<std::string, OptionValue>> options;
  std::string started_utc, finished_utc;  ///< ISO 8601, "2025-01-31T09:30:00Z"
  std::string host;                       ///< host name
  std::string command;  ///< the CLI's command line, or the library call ("python: ...")
};

/// The build's own facts: version(), the source commit and the build type.
struct BuildInfo {
  std::string solver_version, source_commit, build_type;
};
BuildInfo build_info();

/// The scene file at `path` as it is now: its content hash and the files it reads (a file
/// that is missing or unreadable gets sha256 ""). Does not validate the scene. Throws
/// InputError when the scene file cannot be read or is no JSON.
SceneSource scene_file_source(const std::string& path);

/// Why results with `provenance` do not belong to the scene file `scene_path`, one sentence per
/// difference: the scene's content changed, a file it reads changed, is missing, is new or no
/// longer read. Results without provenance, or traced from a scene built in memory, "cannot be
/// verified" (one sentence). Empty: they belong together.
std::vector<std::string> verify_provenance(const std::string& scene_path,
                                           const std::optional<Provenance>& provenance);

/// A results document's "provenance" object from its JSON text ("null": none). InputError
/// naming `source` and the field for anything else.
std::optional<Provenance> provenance_from_json(const std::string& text,
                                               const std::string& source = "");

/// What `lightsolver verify` finds: why a document does not belong to a scene file (empty: it
/// belongs) and, for one that belongs, what it is beside a plain run of the scene.
struct Verification {
  std::vector<std::string> differences;
  std::vector<std::string> notes;  ///< only when it belongs (no differences)
  bool optimization = false;       ///< the document is an optimizer's output, not results
};

/// verify_provenance() for a document's JSON text, by its `format`:
/// - results (read with results_from_json() when `validate`, which names `source` and the field
///   of a document that is no results document; without it only `provenance`, `rescaled`,
///   `groups` and `luminaires` are read): also its flux record. Results whose `rescaled` gives
///   a group a factor (a rescale, a light scene, combined group traces) belong to the scene when
///   its content and files are the traced ones and every luminaire's `dimming` is its group's
///   factor and every group's `flux_lm` the sum of its luminaires' `emitted_flux_lm`: a note
///   names the factors that are not 1.
/// - an optimizer's output (lightsolver.optimization/1): also the optimization block it
///   searched against the scene file's (`provenance.optimization_sha256`); a note says that it
///   holds configurations, not results.
Verification verify_document(const std::string& scene_path, const std::string& text,
                             const std::string& source = "", bool validate = true);

/// verify_document(...).differences for results JSON text.
std::vector<std::string> verify_results(const std::string& scene_path,
                                        const std::string& results_text,
                                        const std::string& source = "");

}  // namespace lightsolver
