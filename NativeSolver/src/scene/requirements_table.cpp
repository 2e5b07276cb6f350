// Requirements on targets from the scene file and from the shipped requirements table.
#include "scene/requirements_table.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "io/json_reader.hpp"

#ifndef LIGHTSOLVER_REQUIREMENTS_DIR
#define LIGHTSOLVER_REQUIREMENTS_DIR ""
#endif

namespace lightsolver::detail {
namespace {

namespace fs = std::filesystem;
constexpr const char* kTableFile = "en12464-1.json";

// Edit distance, for "did you mean" lists of task ids.
std::size_t distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

// The ids closest to `id` (a shared word counts as close too), at most five.
std::string closest_ids(const std::string& id, const nlohmann::json& tasks) {
  std::vector<std::pair<std::size_t, std::string>> ranked;
  for (const auto& row : tasks) {
    const std::string other = row.value("id", "");
    std::size_t d = distance(id, other);
    if (!id.empty() && other.find(id) != std::string::npos) d = 0;
    ranked.emplace_back(d, other);
  }
  std::stable_sort(ranked.begin(), ranked.end());
  std::string list;
  for (std::size_t i = 0; i < ranked.size() && i < 5; ++i) {
    list += (i ? ", " : "") + ranked[i].second;
  }
  return list;
}

struct Table {
  std::string path;
  fs::file_time_type modified;
  nlohmann::json doc;
};

// The table, parsed once per path and version (scene files may name tasks on many targets; a
// long-lived process sees an edited table).
const Table& load_table(const JsonNode& where, const std::string& base_dir) {
  static thread_local Table cached;
  const std::string path = requirements_table_path(base_dir);
  if (path.empty()) {
    where.fail(std::string("no requirements table found (set LIGHTSOLVER_REQUIREMENTS to its "
                           "file, or put ") +
               kTableFile + " next to the scene)");
  }
  std::error_code ec;
  const fs::file_time_type modified = fs::last_write_time(path, ec);
  if (cached.path == path && cached.modified == modified) return cached;
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  Table t{path, modified, parse_json_text(text.str(), path)};
  if (!t.doc.is_object() || !t.doc.contains("tasks") || !t.doc["tasks"].is_array()) {
    throw InputError(path, "tasks", "the requirements table has no \"tasks\" list");
  }
  cached = std::move(t);
  return cached;
}

// The table row `id`: its values fill `r`, its source is named.
void apply_task(const JsonNode& task, const std::string& base_dir, Requirements& r) {
  const std::string id = task.string();
  const Table& table = load_table(task, base_dir);
  for (const auto& row : table.doc["tasks"]) {
    if (row.value("id", "") != id) continue;
    const auto number = [&](const char* key) -> std::optional<double> {
      if (!row.contains(key) || !row[key].is_number()) return std::nullopt;
      return row[key].get<double>();
    };
    r.task = id;
    r.em_lux = number("em_lux");
    r.u0 = number("u0");
    r.ugr_max = number("ugr_l");
    std::string source = table.doc.value("source", table.doc.value("standard", table.path));
    if (row.contains("ref") && row["ref"].is_string()) {
      source += ", ref. " + row["ref"].get<std::string>() + " (2011 numbering)";
    }
    r.source = source + ": " + row.value("name", id);
    return;
  }
  task.fail("unknown task \"" + id + "\" in " + table.path +
            " (closest: " + closest_ids(id, table.doc["tasks"]) + ")");
}

}  // namespace

std::string requirements_table_path(const std::string& base_dir) {
  std::vector<fs::path> candidates;
  if (const char* env = std::getenv("LIGHTSOLVER_REQUIREMENTS"); env && *env) {
    candidates.emplace_back(env);
  }
  if (!base_dir.empty()) candidates.push_back(fs::path(base_dir) / kTableFile);
  if (*LIGHTSOLVER_REQUIREMENTS_DIR) {
    candidates.push_back(fs::path(LIGHTSOLVER_REQUIREMENTS_DIR) / kTableFile);
  }
  for (const fs::path& p : candidates) {
    std::error_code ec;
    if (fs::is_regular_file(p, ec)) return p.lexically_normal().string();
  }
  return {};
}

Requirements read_requirements(const JsonNode& n, const std::string& base_dir) {
  Requirements r;
  if (n.has("task")) apply_task(n.at("task"), base_dir, r);
  if (!n.has("requirements")) return r;
  const JsonNode q = n.at("requirements");
  q.require_object({"em_lux", "u0", "emin_lux", "ud", "ugr_max", "df_target_percent",
                    "df_minimum_percent", "en17037", "median_diffuse_lx"});
  if (q.has("em_lux")) r.em_lux = q.at("em_lux").number();
  if (q.has("u0")) r.u0 = q.at("u0").number();
  if (q.has("emin_lux")) r.emin_lux = q.at("emin_lux").number();
  if (q.has("ud")) r.ud = q.at("ud").number();
  if (q.has("ugr_max")) r.ugr_max = q.at("ugr_max").number();
  if (q.has("df_target_percent")) r.df_target_percent = q.at("df_target_percent").number();
  if (q.has("df_minimum_percent")) r.df_minimum_percent = q.at("df_minimum_percent").number();
  if (q.has("median_diffuse_lx")) r.median_diffuse_lx = q.at("median_diffuse_lx").number();
  if (q.has("en17037")) {
    const std::string level = q.at("en17037").string();
    const auto l = en17037_level(level);
    if (!l) {
      q.at("en17037").fail("expected \"minimum\", \"medium\" or \"high\" (EN 17037:2018), got \"" +
                           level + "\"");
    }
    r.en17037 = *l;
    r.source = std::string("EN 17037:2018, daylight factor method, ") + level;
  }
  return r;
}

}  // namespace lightsolver::detail
