// Provenance of results: the scene's content hash and the files it reads, and what a run
// records about itself (lightsolver/provenance.hpp). JSON both ways and verification:
// provenance_io.cpp.
#include "scene/provenance.hpp"

#include <dlfcn.h>
#include <openssl/evp.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <climits>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "lightsolver/run_options.hpp"
#include "scene/requirements_table.hpp"

#ifndef LIGHTSOLVER_BUILD_TYPE
#define LIGHTSOLVER_BUILD_TYPE ""
#endif

namespace lightsolver::detail {
namespace {

namespace fs = std::filesystem;

// libcrypto's SHA-256, loaded at the first hash: the scene's hash runs on a thread beside the
// reading, so loading the library there (about 1 ms) is off the way to the first photon,
// where linking it made every process load it before main (docs/BENCHMARKS.md, "Start-up").
struct Sha256Api {
  EVP_MD_CTX* (*ctx_new)() = nullptr;
  void (*ctx_free)(EVP_MD_CTX*) = nullptr;
  const EVP_MD* (*sha256)() = nullptr;
  int (*init)(EVP_MD_CTX*, const EVP_MD*, ENGINE*) = nullptr;
  int (*update)(EVP_MD_CTX*, const void*, std::size_t) = nullptr;
  int (*final)(EVP_MD_CTX*, unsigned char*, unsigned int*) = nullptr;
};

const Sha256Api& sha256_api() {
  static Sha256Api api;
  static std::once_flag once;
  std::call_once(once, [] {
    void* lib = dlopen(LIGHTSOLVER_CRYPTO_SONAME, RTLD_NOW | RTLD_LOCAL);
    if (lib == nullptr) return;
    auto get = [&](auto& f, const char* name) {
      f = reinterpret_cast<std::remove_reference_t<decltype(f)>>(dlsym(lib, name));
    };
    get(api.ctx_new, "EVP_MD_CTX_new");
    get(api.ctx_free, "EVP_MD_CTX_free");
    get(api.sha256, "EVP_sha256");
    get(api.init, "EVP_DigestInit_ex");
    get(api.update, "EVP_DigestUpdate");
    get(api.final, "EVP_DigestFinal_ex");
  });
  return api;
}

struct DigestDeleter {
  void operator()(EVP_MD_CTX* c) const { sha256_api().ctx_free(c); }
};
using Digest = std::unique_ptr<EVP_MD_CTX, DigestDeleter>;

Digest new_sha256() {
  const Sha256Api& api = sha256_api();
  if (!api.ctx_new || !api.ctx_free || !api.sha256 || !api.init || !api.update || !api.final) {
    throw std::runtime_error(std::string("SHA-256 is not available (OpenSSL libcrypto, ") +
                             LIGHTSOLVER_CRYPTO_SONAME + ")");
  }
  Digest d(api.ctx_new());
  if (!d || api.init(d.get(), api.sha256(), nullptr) != 1) {
    throw std::runtime_error("SHA-256 is not available (OpenSSL libcrypto)");
  }
  return d;
}

void update(EVP_MD_CTX* d, const char* data, std::size_t n) {
  if (sha256_api().update(d, data, n) != 1) throw std::runtime_error("SHA-256 update failed");
}

std::string hex_of(EVP_MD_CTX* d) {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int n = 0;
  if (sha256_api().final(d, digest, &n) != 1) throw std::runtime_error("SHA-256 failed");
  static const char* kHex = "0123456789abcdef";
  std::string out;
  for (unsigned int i = 0; i < n; ++i) {
    out += kHex[digest[i] >> 4];
    out += kHex[digest[i] & 15];
  }
  return out;
}

// Integral values below 2^53 become integers, so the text does not depend on how the number
// was spelled (1, 1.0, 1e0); everything else is kept as parsed.
nlohmann::json normalized(const nlohmann::json& j) {
  if (j.is_object()) {
    nlohmann::json out = nlohmann::json::object();
    for (const auto& [key, value] : j.items()) out[key] = normalized(value);
    return out;
  }
  if (j.is_array()) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& value : j) out.push_back(normalized(value));
    return out;
  }
  if (j.is_number_float()) {
    const double v = j.get<double>();
    constexpr double kExact = 9007199254740992.0;  // 2^53
    if (std::isfinite(v) && std::trunc(v) == v && std::abs(v) < kExact) {
      return v < 0 ? nlohmann::json(static_cast<std::int64_t>(v))
                   : nlohmann::json(static_cast<std::uint64_t>(v));
    }
  }
  if (j.is_number_integer() && !j.is_number_unsigned() && j.get<std::int64_t>() >= 0) {
    return j.get<std::uint64_t>();  // a Python int and a parsed one: the same kind
  }
  return j;
}

// Files in the order the scene names them, each path once.
class FileList {
 public:
  FileList(const std::string& base_dir, const std::string& scene_file, bool strict)
      : base_dir_(base_dir), scene_file_(scene_file), strict_(strict) {}

  void add(const std::string& written, const std::string& resolved, const std::string& kind,
           const std::string& where) {
    for (const SourceFile& f : files_) {
      if (f.path == written) return;
    }
    std::optional<std::string> sha = file_sha256(resolved);
    if (!sha && strict_) {
      throw InputError(scene_file_, where, "cannot read \"" + resolved + "\" to record its hash");
    }
    files_.push_back({written, kind, sha.value_or("")});
  }

  // Every string "file" in the entries of list `key`.
  void add_entries(const nlohmann::json& doc, const char* key, const char* default_kind) {
    if (!doc.contains(key) || !doc[key].is_array()) return;
    const nlohmann::json& list = doc[key];
    for (std::size_t i = 0; i < list.size(); ++i) {
      const nlohmann::json& e = list[i];
      if (!e.is_object() || !e.contains("file") || !e["file"].is_string()) continue;
      const std::string written = e["file"].get<std::string>();
      const bool photometric = e.contains("type") && e["type"] == "photometric";
      add(written, (fs::path(base_dir_) / written).lexically_normal().string(),
          photometric ? "photometric" : default_kind,
          std::string(key) + "[" + std::to_string(i) + "].file");
    }
  }

  // The requirements table, when a target names a task: found by search (requirements_table.hpp),
  // so it is listed by its file name.
  void add_requirements_table(const nlohmann::json& doc) {
    if (!doc.contains("targets") || !doc["targets"].is_array()) return;
    const auto& targets = doc["targets"];
    const bool tasks = std::any_of(targets.begin(), targets.end(), [](const nlohmann::json& t) {
      return t.is_object() && t.contains("task");
    });
    if (!tasks) return;
    const std::string path = requirements_table_path(base_dir_);
    if (path.empty()) {
      if (strict_) throw InputError(scene_file_, "targets", "no requirements table found");
      files_.push_back({"en12464-1.json", "requirements table", ""});
      return;
    }
    add(fs::path(path).filename().string(), path, "requirements table", "targets");
  }

  std::vector<SourceFile> take() { return std::move(files_); }

 private:
  std::string base_dir_, scene_file_;
  bool strict_;
  std::vector<SourceFile> files_;
};

// Resolved value of run option `name` in a run that produced `r`. Every row of the table is
// named here (a new row without a line fails every run's provenance, so it cannot be missed).
OptionValue resolved_option(std::string_view name, const Results& r, const Scene& scene) {
  const auto optional = [](const std::optional<double>& v) {
    return v ? OptionValue(*v) : OptionValue();
  };
  if (name == "photons") return r.photons_requested;
  if (name == "seed") return r.seed;
  if (name == "confidence") return r.confidence;
  if (name == "target_accuracy") return optional(r.target_accuracy);
  if (name == "accuracy_per_cell") return r.accuracy_per_cell;
  if (name == "max_seconds") return optional(r.max_seconds);
  if (name == "decide") return r.decide;
  if (name == "contributions") return r.contributions;
  if (name == "next_event") return r.next_event;
  if (name == "connect_reflections") return r.connect_reflections;
  if (name == "max_bounces") return std::uint64_t{scene.settings.max_bounces};
  if (name == "sampler") return r.sampler;
  if (name == "replicates") {
    return r.replicates ? OptionValue(std::uint64_t{r.replicates}) : OptionValue();
  }
  throw std::logic_error("provenance: run option \"" + std::string(name) +
                         "\" has no resolved value (provenance.cpp)");
}

}  // namespace

std::string host_name() {
  char name[HOST_NAME_MAX + 1] = {};
  if (gethostname(name, sizeof name - 1) != 0 || !name[0]) return "unknown";
  return name;
}

std::string sha256_hex(std::string_view bytes) {
  Digest d = new_sha256();
  update(d.get(), bytes.data(), bytes.size());
  return hex_of(d.get());
}

std::optional<std::string> file_sha256(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  Digest d = new_sha256();
  std::vector<char> buffer(1 << 20);
  while (in) {
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    update(d.get(), buffer.data(), static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad()) return std::nullopt;
  return hex_of(d.get());
}

std::string canonical_json(const nlohmann::json& doc) { return normalized(doc).dump(); }

namespace {

// canonical_json's bytes written straight into a SHA-256, without the normalized copy of the
// document or the whole text: on a scene with large inline meshes that copy and text cost more
// than parsing the file. Scalars are written as nlohmann's dump() writes them (its float
// formatting, its string escaping), so the hash is the same (provenance_test.cpp checks).
class CanonicalHasher {
 public:
  CanonicalHasher() : digest_(new_sha256()) { buffer_.reserve(kFlushAt + 512); }

  std::string hex(const nlohmann::json& doc) {
    write(doc);
    flush();
    return hex_of(digest_.get());
  }

 private:
  static constexpr std::size_t kFlushAt = 1 << 16;

  void write(const nlohmann::json& j) {
    switch (j.type()) {
      case nlohmann::json::value_t::object: {
        buffer_ += '{';
        bool first = true;
        for (const auto& [key, value] : j.items()) {
          if (!first) buffer_ += ',';
          first = false;
          buffer_ += nlohmann::json(key).dump();
          buffer_ += ':';
          write(value);
        }
        buffer_ += '}';
        break;
      }
      case nlohmann::json::value_t::array: {
        buffer_ += '[';
        for (std::size_t i = 0; i < j.size(); ++i) {
          if (i > 0) buffer_ += ',';
          write(j[i]);
        }
        buffer_ += ']';
        break;
      }
      case nlohmann::json::value_t::number_float:
        write_float(j.get<double>());
        break;
      case nlohmann::json::value_t::number_integer:
        write_integer(j.get<std::int64_t>());
        break;
      case nlohmann::json::value_t::number_unsigned:
        write_integer(j.get<std::uint64_t>());
        break;
      default:  // strings, booleans, null (and nothing a parse gives besides)
        buffer_ += j.dump();
    }
    if (buffer_.size() >= kFlushAt) flush();
  }

  // As normalized(): an integral value below 2^53 is an integer.
  void write_float(double v) {
    constexpr double kExact = 9007199254740992.0;  // 2^53
    if (std::isfinite(v) && std::trunc(v) == v && std::abs(v) < kExact) {
      if (v < 0) {
        write_integer(static_cast<std::int64_t>(v));
      } else {
        write_integer(static_cast<std::uint64_t>(v));
      }
      return;
    }
    if (!std::isfinite(v)) {
      buffer_ += "null";
      return;
    }
    char text[64];
    buffer_.append(text, ::nlohmann::detail::to_chars(text, text + sizeof text, v));
  }

  template <class Int>
  void write_integer(Int v) {
    char text[24];
    buffer_.append(text, std::to_chars(text, text + sizeof text, v).ptr);
  }

  void flush() {
    update(digest_.get(), buffer_.data(), buffer_.size());
    buffer_.clear();
  }

  Digest digest_;
  std::string buffer_;
};

}  // namespace

std::string canonical_sha256(const nlohmann::json& doc) { return CanonicalHasher().hex(doc); }

SceneSource scene_source(const nlohmann::json& doc, const std::string& base_dir,
                         const std::string& scene_file, bool strict) {
  FileList files(base_dir, scene_file, strict);
  files.add_entries(doc, "meshes", "mesh");
  files.add_entries(doc, "luminaires", "file");
  files.add_entries(doc, "targets", "file");
  files.add_requirements_table(doc);
  return {canonical_sha256(doc), files.take()};
}

std::string utc_text(std::chrono::system_clock::time_point t) {
  const std::time_t s = std::chrono::system_clock::to_time_t(t);
  std::tm tm{};
  gmtime_r(&s, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

Provenance run_provenance(const Scene& scene, const SolveOptions& options, const Results& r,
                          int threads, const std::string& device,
                          std::chrono::system_clock::time_point started,
                          std::chrono::system_clock::time_point finished) {
  Provenance p;
  if (scene.source) {
    p.scene_sha256 = scene.source->sha256;
    p.files = scene.source->files;
  }
  const BuildInfo build = build_info();
  p.solver_version = build.solver_version;
  p.source_commit = build.source_commit;
  p.build_type = build.build_type;
  p.backend = r.backend;
  p.device = device;
  p.mpi_ranks = options.processes ? options.processes->size() : 1;
  p.threads = threads;
  for_each_run_option([&](const auto& row) {
    const std::string_view name = row.info.name;
    if (name == "threads" || name == "backend") return;  // fields of their own
    p.options.emplace_back(row.info.name, resolved_option(name, r, scene));
  });
  std::sort(p.options.begin(), p.options.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  p.started_utc = utc_text(started);
  p.finished_utc = utc_text(finished);
  p.host = host_name();
  p.command = options.command.empty() ? "library call" : options.command;
  return p;
}

}  // namespace lightsolver::detail

namespace lightsolver {

BuildInfo build_info() {
  const std::string type = LIGHTSOLVER_BUILD_TYPE;
  return {version(), detail::source_commit(), type.empty() ? "unspecified" : type};
}

}  // namespace lightsolver
