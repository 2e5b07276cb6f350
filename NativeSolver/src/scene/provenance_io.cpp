// The results' "provenance" object both ways, and whether results belong to a scene file
// (`lightsolver verify`, Python's lightsolver.verify_results).
#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>

#include "lightsolver/defaults.hpp"
#include "lightsolver/results_io.hpp"
#include "scene/provenance.hpp"
#include "scene/scene_document.hpp"

namespace lightsolver {
namespace detail {
namespace {

nlohmann::json option_json(const OptionValue& v) {
  return std::visit(
      [](const auto& x) -> nlohmann::json {
        if constexpr (std::is_same_v<std::decay_t<decltype(x)>, std::monostate>) {
          return nullptr;
        } else {
          return x;
        }
      },
      v);
}

OptionValue read_option(const JsonNode& n, const nlohmann::json& j) {
  if (j.is_null()) return {};
  if (j.is_boolean()) return j.get<bool>();
  if (j.is_number_unsigned()) return j.get<std::uint64_t>();
  if (j.is_number_float()) return n.number();
  if (j.is_string()) return j.get<std::string>();
  n.fail("expected null, true, false, a non-negative integer, a number or a string");
}

int read_count(const JsonNode& n) {
  const std::uint64_t v = n.unsigned_integer();
  if (v > std::uint64_t(INT_MAX)) n.fail("too large");
  return static_cast<int>(v);
}

// "photometric file "ies/a.ies"", "the requirements table "en12464-1.json"".
std::string describe(const SourceFile& f) {
  if (f.kind == "requirements table") return "the requirements table \"" + f.path + "\"";
  return f.kind + (f.kind == "file" ? " \"" : " file \"") + f.path + "\"";
}

}  // namespace

nlohmann::json provenance_json(const Provenance& p) {
  nlohmann::json files = nlohmann::json::array();
  for (const SourceFile& f : p.files) {
    files.push_back({{"path", f.path}, {"kind", f.kind}, {"sha256", f.sha256}});
  }
  nlohmann::json options = nlohmann::json::object();
  for (const auto& [name, value] : p.options) options[name] = option_json(value);
  return {{"scene_sha256", p.scene_sha256 ? nlohmann::json(*p.scene_sha256) : nullptr},
          {"files", std::move(files)},
          {"solver_version", p.solver_version},
          {"source_commit", p.source_commit},
          {"build_type", p.build_type},
          {"backend", p.backend},
          {"device", p.device},
          {"mpi_ranks", p.mpi_ranks},
          {"threads", p.threads},
          {"options", std::move(options)},
          {"started_utc", p.started_utc},
          {"finished_utc", p.finished_utc},
          {"host", p.host},
          {"command", p.command}};
}

Provenance read_provenance(const JsonNode& n) {
  Provenance p;
  if (!n.at("scene_sha256").is_null()) p.scene_sha256 = n.at("scene_sha256").string();
  const JsonNode files = n.at("files");
  for (std::size_t i = 0; i < files.array_size(); ++i) {
    p.files.push_back({files[i].at("path").string(), files[i].at("kind").string(),
                       files[i].at("sha256").string()});
  }
  p.solver_version = n.at("solver_version").string();
  p.source_commit = n.at("source_commit").string();
  p.build_type = n.at("build_type").string();
  p.backend = n.at("backend").string();
  p.device = n.at("device").string();
  p.mpi_ranks = read_count(n.at("mpi_ranks"));
  p.threads = read_count(n.at("threads"));
  const JsonNode options = n.at("options");
  for (const auto& item : options.object().items()) {
    const JsonNode one(item.value(), options.path() + "." + item.key(), n.file());
    p.options.emplace_back(item.key(), read_option(one, item.value()));
  }
  p.started_utc = n.at("started_utc").string();
  p.finished_utc = n.at("finished_utc").string();
  p.host = n.at("host").string();
  p.command = n.at("command").string();
  return p;
}

}  // namespace detail

SceneSource scene_file_source(const std::string& path) {
  const nlohmann::json doc = detail::parse_json_text(detail::read_scene_text(path), path);
  return detail::scene_source(doc, std::filesystem::path(path).parent_path().string(), path, false);
}

std::optional<Provenance> provenance_from_json(const std::string& text, const std::string& source) {
  const nlohmann::json doc = detail::parse_json_text(text, source);
  if (doc.is_null()) return std::nullopt;
  return detail::read_provenance(detail::JsonNode(doc, "provenance", source));
}

std::vector<std::string> verify_provenance(const std::string& scene_path,
                                           const std::optional<Provenance>& provenance) {
  if (!provenance) {
    return {
        "the results carry no provenance (written by a solver that did not record it, or "
        "removed since): they cannot be verified against this scene; trace it again"};
  }
  if (!provenance->scene_sha256) {
    return {
        "the results were traced from a scene built or changed in memory, not read from a "
        "file: they cannot be verified against this scene; trace the scene file"};
  }
  const SceneSource now = scene_file_source(scene_path);
  std::vector<std::string> out;
  if (*provenance->scene_sha256 != now.sha256) {
    out.push_back(
        "the scene's content differs from the scene the results were traced from "
        "(it was changed since, or the results are another scene's)");
  }
  std::map<std::string, const SourceFile*> current;
  for (const SourceFile& f : now.files) current[f.path] = &f;
  for (const SourceFile& traced : provenance->files) {
    const auto it = current.find(traced.path);
    if (it == current.end()) {
      out.push_back("the results were traced with " + detail::describe(traced) +
                    ", which the scene does not read now");
    } else if (it->second->sha256.empty()) {
      out.push_back(detail::describe(traced) + " is missing or cannot be read");
    } else if (it->second->sha256 != traced.sha256) {
      out.push_back(detail::describe(traced) + " changed since the results were traced");
    }
  }
  std::map<std::string, const SourceFile*> traced;
  for (const SourceFile& f : provenance->files) traced[f.path] = &f;
  for (const SourceFile& f : now.files) {
    if (traced.contains(f.path)) continue;
    out.push_back("the scene now reads " + detail::describe(f) +
                  (f.sha256.empty() ? " (missing or unreadable)" : "") +
                  ", which the results were not traced with");
  }
  return out;
}

namespace {

std::string number_text(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

double number_or(const nlohmann::json& j, const char* key, double fallback) {
  return j.is_object() && j.contains(key) && j[key].is_number() ? j[key].get<double>() : fallback;
}

std::string text_or(const nlohmann::json& j, const char* key) {
  return j.is_object() && j.contains(key) && j[key].is_string() ? j[key].get<std::string>() : "";
}

// "Fluxes as recorded": every luminaire dimmed by its group's factor in `rescaled` (1 without
// one) and every group's flux the sum of its luminaires' emitted flux, as the solver writes them
// (a run, a rescale, combined group traces). Results from before `luminaires` have nothing to
// check. The factors that are not 1 are noted: the results are the scene's light with them.
void check_flux_record(const nlohmann::json& doc, Verification& v) {
  std::map<std::string, double> factor;
  if (doc.contains("rescaled") && doc["rescaled"].is_object()) {
    for (const auto& [name, f] : doc["rescaled"].items()) {
      if (f.is_number()) factor[name] = f.get<double>();
    }
  }
  const nlohmann::json none = nlohmann::json::array();
  const nlohmann::json& groups = doc.contains("groups") ? doc["groups"] : none;
  const nlohmann::json& luminaires = doc.contains("luminaires") ? doc["luminaires"] : none;
  if (!groups.is_array() || !luminaires.is_array()) return;
  std::map<std::string, double> emitted;
  for (const nlohmann::json& l : luminaires) {
    const std::string group = text_or(l, "group");
    const auto f = factor.find(group);
    const double expected = f == factor.end() ? 1.0 : f->second;
    const double dimming = number_or(l, "dimming", expected);
    if (!(std::abs(dimming - expected) <= 1e-12 * std::max(1.0, expected))) {
      v.differences.push_back("luminaire \"" + text_or(l, "name") + "\" is dimmed by " +
                              number_text(dimming) + " but its group \"" + group + "\" by " +
                              number_text(expected) +
                              ": the results' flux record is not the solver's");
    }
    emitted[group] += number_or(l, "emitted_flux_lm", 0.0);
  }
  std::map<std::string, bool> known;
  for (const nlohmann::json& g : groups) {
    const std::string name = text_or(g, "name");
    known[name] = true;
    const double flux = number_or(g, "flux_lm", 0.0);
    if (!luminaires.empty() && !(std::abs(flux - emitted[name]) <= 1e-9 * std::max(1.0, flux))) {
      v.differences.push_back("luminaire group \"" + name + "\" emits " + number_text(flux) +
                              " lm, its luminaires " + number_text(emitted[name]) +
                              " lm: the results' flux record is not the solver's");
    }
  }
  std::string scaled;
  for (const auto& [name, f] : factor) {
    if (!groups.empty() && !known.contains(name)) {
      v.differences.push_back("the results rescale luminaire group \"" + name +
                              "\", which they do not hold");
    } else if (f != 1.0) {
      scaled += (scaled.empty() ? "" : ", ") + ("\"" + name + "\" x " + number_text(f));
    }
  }
  if (!scaled.empty()) {
    v.notes.push_back(
        "the same trace with other group fluxes: the scene's fluxes times the "
        "recorded factors (rescaled): " +
        scaled);
  }
}

// An optimizer's output: its provenance and the optimization block it searched.
void verify_optimization(const std::string& scene_path, const nlohmann::json& doc,
                         const std::string& source, Verification& v) {
  v.optimization = true;
  if (!doc.contains("provenance") || doc["provenance"].is_null()) {
    v.differences.push_back(
        "the optimizer's output carries no provenance (written by a solver that did not record "
        "it): it cannot be verified against this scene; run the search again");
    return;
  }
  const std::optional<Provenance> p =
      detail::read_provenance(detail::JsonNode(doc["provenance"], "provenance", source));
  v.differences = verify_provenance(scene_path, p);
  if (p->scene_sha256) {
    const nlohmann::json scene =
        detail::parse_json_text(detail::read_scene_text(scene_path), scene_path);
    const std::string searched = text_or(doc["provenance"], "optimization_sha256");
    const std::string now = scene.contains("optimization")
                                ? detail::sha256_hex(detail::canonical_json(scene["optimization"]))
                                : "";
    if (now.empty()) {
      v.differences.push_back("the scene has no optimization block now");
    } else if (searched != now) {
      v.differences.push_back(
          "the optimization block searched differs from the scene's (changed since, or given "
          "in its place)");
    }
  }
  v.notes.push_back(
      "an optimizer's output (lightsolver.optimization/1), not results: each ISOC member is the "
      "scene with its values applied (docs/optimization.md, \"Provenance and configurations\")");
}

// Results: read in full (`validate`) or only their provenance and flux record (Python's dicts).
void verify_results_document(const std::string& scene_path, const nlohmann::json& doc,
                             const std::string& text, const std::string& source, bool validate,
                             Verification& v) {
  std::optional<Provenance> p;
  if (validate) {
    p = results_from_json(text, source).provenance;
  } else if (doc.is_object() && doc.contains("provenance") && !doc["provenance"].is_null()) {
    p = detail::read_provenance(detail::JsonNode(doc["provenance"], "provenance", source));
  }
  v.differences = verify_provenance(scene_path, p);
  if (p) check_flux_record(doc, v);
}

}  // namespace

Verification verify_document(const std::string& scene_path, const std::string& text,
                             const std::string& source, bool validate) {
  const nlohmann::json doc = detail::parse_json_text(text, source);
  Verification v;
  if (doc.is_object() && doc.contains("format") && doc["format"] == kOptimizationFormat) {
    verify_optimization(scene_path, doc, source, v);
  } else {
    verify_results_document(scene_path, doc, text, source, validate, v);
  }
  if (!v.differences.empty()) v.notes.clear();
  return v;
}

std::vector<std::string> verify_results(const std::string& scene_path,
                                        const std::string& results_text,
                                        const std::string& source) {
  return verify_document(scene_path, results_text, source).differences;
}

}  // namespace lightsolver
