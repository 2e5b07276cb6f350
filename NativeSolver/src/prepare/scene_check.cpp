// The one scene check (scene_check.hpp): validate() for the errors, then what a run would warn
// about before tracing, each warning located by the scene field it concerns.
#include "lightsolver/scene_check.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <vector>

#include "lightsolver/scene_io.hpp"
#include "model/coincident.hpp"
#include "model/prepared_scene.hpp"
#include "prepare/target_reach.hpp"
#include "scene/scene_document.hpp"

namespace lightsolver {

namespace {

// Scene warnings start with the path they concern ("settings.confidence: ...",
// "meshes[2] (\"floor\"): dropped ..."): the leading run of path characters, when one follows.
std::string leading_path(const std::string& text) {
  std::size_t n = 0;
  while (n < text.size() && (std::isalnum(static_cast<unsigned char>(text[n])) || text[n] == '_' ||
                             text[n] == '.' || text[n] == '[' || text[n] == ']')) {
    ++n;
  }
  if (n == 0 || n == text.size() || (text[n] != ':' && text[n] != ' ')) return "";
  return text.substr(0, n).find_first_of(".[") == std::string::npos ? "" : text.substr(0, n);
}

std::string at(const char* list, std::size_t i) {
  return std::string(list) + "[" + std::to_string(i) + "]";
}

std::string one_decimal(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", v);
  return buf;
}
std::string two_digits(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2g", v);
  return buf;
}

// A sky without portals emits from a disc of its site's radius R across every direction
// (docs/daylight.md, "Emission"). A scene point farther than R from the site's centre misses part
// of the sky (a wrong result, not a slow one); and a scene within r of its own centre catches at
// most (r/R)² of the photons, since its shadow on any disc fits in a circle of radius r. Both are
// found from the meshes' vertices and the targets' points (the convex hull's farthest points):
// linear in the vertices, no tracing. Whether a room is closed is not judged (that needs
// tracing); the photon share says what portals would gain.
template <class Warn>
void add_sky_site_warnings(const Scene& scene, Warn&& warn) {
  std::vector<glm::dvec3> points;
  for (const Mesh& m : scene.meshes)
    points.insert(points.end(), m.vertices.begin(), m.vertices.end());
  for (const Target& t : scene.targets) {
    if (t.type == Target::Type::Observer) {
      points.push_back(t.position);
    } else if (t.type != Target::Type::Surface) {
      points.insert(points.end(), {t.corner, t.corner + t.edge1, t.corner + t.edge2,
                                   t.corner + t.edge1 + t.edge2});
      points.insert(points.end(), t.positions.begin(), t.positions.end());
    }
  }
  if (points.empty()) return;
  glm::dvec3 lo = points.front(), hi = points.front();
  for (const glm::dvec3& p : points) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const glm::dvec3 mid = 0.5 * (lo + hi);
  for (std::size_t i = 0; i < scene.luminaires.size(); ++i) {
    const Luminaire& l = scene.luminaires[i];
    if (l.type != Luminaire::Type::Sky || !l.sky.portals.empty()) continue;
    const double R = l.sky.site_radius_m;
    double far = 0.0, r = 0.0;
    for (const glm::dvec3& p : points) {
      far = std::max(far, glm::length(p - l.sky.site_centre));
      r = std::max(r, glm::length(p - mid));
    }
    const std::string field = at("luminaires", i) + ".site";
    if (far > R) {
      warn(field, "the scene reaches " + one_decimal(far) + " m from the site's centre, beyond " +
                      "its radius_m " + one_decimal(R) +
                      " m: points out there do not receive the "
                      "whole sky and ground; give radius_m >= " +
                      one_decimal(far) + " m");
    } else if (r < 0.5 * R) {
      warn(field, "at most " + two_digits(100.0 * r * r / (R * R)) +
                      " % of the sky's photons can reach the scene (it lies within " +
                      one_decimal(r) + " m of its centre, the site's radius is " + one_decimal(R) +
                      " m): a smaller radius_m, or portals on the openings (every photon enters "
                      "the room), give the same answer for less work");
    }
  }
}

// Whether the ray o + t d (t > 0) meets triangle abc (Möller & Trumbore 1997, in double).
bool ray_meets(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& a, const glm::dvec3& b,
               const glm::dvec3& c) {
  const glm::dvec3 e1 = b - a, e2 = c - a, p = glm::cross(d, e2);
  const double det = glm::dot(e1, p);
  if (std::abs(det) < 1e-300) return false;
  const glm::dvec3 s = o - a;
  const double u = glm::dot(s, p) / det;
  if (u < 0.0 || u > 1.0) return false;
  const glm::dvec3 q = glm::cross(s, e1);
  const double v = glm::dot(d, q) / det;
  return v >= 0.0 && u + v <= 1.0 && glm::dot(e2, q) / det > 1e-9;
}

// A sky without portals lighting a closed room with openings (docs/daylight.md, "Emission"):
// it is right but slow, every photon that does not pass an opening wasted. Decided from the
// geometry alone, per grid or observer target: of 256 directions spread evenly over the sphere
// (a Fibonacci lattice) from its centre, some reach the open sky and at least 3/4 meet a
// triangle: the target sits in a room open to the sky only through its openings (a room with
// no opening at all, or a target out in the open, draws no remark). Brute force, so only for
// scenes of up to 100 000 triangles (a few 10^7 ray-triangle tests at most per target).
template <class Warn>
void add_closed_room_warnings(const Scene& scene, Warn&& warn) {
  constexpr int kDirections = 256;
  constexpr std::size_t kMaxTriangles = 100'000, kMaxTargets = 8;
  std::size_t triangles = 0;
  for (const Mesh& m : scene.meshes) triangles += m.triangles.size();
  if (triangles == 0 || triangles > kMaxTriangles) return;
  std::vector<std::size_t> skies;
  for (std::size_t i = 0; i < scene.luminaires.size(); ++i) {
    const Luminaire& l = scene.luminaires[i];
    if (l.type == Luminaire::Type::Sky && l.sky.portals.empty() && l.flux_lm > 0.0) {
      skies.push_back(i);
    }
  }
  if (skies.empty()) return;
  std::size_t checked = 0;
  for (std::size_t t = 0; t < scene.targets.size() && checked < kMaxTargets; ++t) {
    const Target& target = scene.targets[t];
    if (target.type == Target::Type::Surface) continue;
    ++checked;
    const glm::dvec3 o = target.type == Target::Type::Observer
                             ? target.position
                             : target.corner + 0.5 * (target.edge1 + target.edge2);
    int blocked = 0;
    for (int k = 0; k < kDirections; ++k) {
      const double z = 1.0 - (2.0 * k + 1.0) / kDirections, r = std::sqrt(1.0 - z * z);
      const double phi = 2.399963229728653 * k;  // the golden angle
      const glm::dvec3 d(r * std::cos(phi), r * std::sin(phi), z);
      bool hit = false;
      for (const Mesh& m : scene.meshes) {
        for (const auto& tri : m.triangles) {
          if (ray_meets(o, d, m.vertices[tri[0]], m.vertices[tri[1]], m.vertices[tri[2]])) {
            hit = true;
            break;
          }
        }
        if (hit) break;
      }
      blocked += hit ? 1 : 0;
    }
    if (blocked == kDirections || 4 * blocked < 3 * kDirections) continue;
    for (std::size_t i : skies) {
      warn(at("luminaires", i) + ".portals",
           "closed room with openings but no portals: from target \"" + target.name + "\" only " +
               one_decimal(100.0 * (kDirections - blocked) / kDirections) +
               " % of the directions reach the sky, so most of the sky's photons from its site "
               "disc are wasted; portals on the openings give the same answer for far less work "
               "(outside surfaces then act black: docs/daylight.md, \"Portals and outside "
               "obstructions\")");
    }
    return;  // one remark per sky is enough
  }
}

// What Simulation would add to Results::warnings before the first photon, per field.
void add_run_warnings(const Scene& scene, SceneCheck& out) {
  auto warn = [&](std::string field, std::string message) {
    out.warnings.push_back({scene.source_file, std::move(field), 0, std::move(message)});
  };
  add_sky_site_warnings(scene, warn);
  add_closed_room_warnings(scene, warn);
  // A scene validated before (load_scene's, then check_scene's copy) may repeat a remark.
  Warnings seen;
  for (const std::string& w : scene.warnings) {
    if (std::find(seen.begin(), seen.end(), w) != seen.end()) continue;
    seen.push_back(w);
    warn(leading_path(w), w);
  }
  for (std::size_t i = 0; i < scene.luminaires.size(); ++i) {
    for (const std::string& w : photometric_warnings(scene.luminaires[i])) {
      warn(at("luminaires", i), w);
    }
  }
  // 0 lm is a switched-off luminaire (docs/scene-format.md); only a scene that emits nothing
  // at all is worth a remark.
  if (!scene.luminaires.empty() && scene.total_flux_lm() <= 0.0) {
    warn("luminaires", "all luminaires have zero flux: every result will be 0 lx");
  }
  // Coincident surfaces are found by prepare(), as in a run (about linear in the triangles).
  const detail::PreparedScene prepared = detail::prepare(scene);
  for (const detail::Coincidence& c : prepared.coincidences) {
    for (const std::string& w : detail::coincidence_warnings(scene, {c})) {
      warn(at("meshes", c.a), w);
    }
  }
  // Targets no light can reach (no surface reflects and they face away from every luminaire).
  for (const detail::DarkTarget& d :
       detail::dark_targets(scene, prepared, detail::analyse_effects(prepared))) {
    warn(at("targets", d.target), d.message);
  }
}

// Reads the scene (a reading error is the one error), then collects every validation error;
// a valid scene gets the run's warnings.
template <class Load>
SceneCheck check_loaded(Load load) {
  SceneCheck out;
  try {
    Scene scene = load();
    for (const InputError& e : validation_errors(scene)) out.errors.push_back(issue_from_error(e));
    if (out.errors.empty()) add_run_warnings(scene, out);
  } catch (const InputError& e) {
    out.errors.push_back(issue_from_error(e));
  } catch (const std::exception& e) {  // unreadable file, out of memory: still one error
    out.errors.push_back({"", "", 0, e.what()});
  }
  return out;
}

}  // namespace

SceneIssue issue_from_error(const InputError& error) {
  SceneIssue issue{error.file(), error.where(), 0, error.what()};
  // The message without the "file: where: " InputError puts in front (file and field are kept
  // apart here).
  const std::string& where = error.where();
  const std::string prefix = (error.file().empty() ? std::string("<scene>") : error.file()) +
                             (where.empty() ? "" : ": " + where) + ": ";
  if (issue.message.rfind(prefix, 0) == 0) issue.message.erase(0, prefix.size());
  if (where.rfind("line ", 0) == 0) {
    try {
      issue.line = std::stoi(where.substr(5));
      issue.field.clear();
    } catch (const std::exception&) {  // "line" followed by no number: keep it as the field
    }
  }
  return issue;
}

SceneCheck check_scene(const Scene& scene) {
  return check_loaded([&] { return scene; });
}

SceneCheck check_scene_file(const std::string& path) {
  return check_loaded([&] {
    return detail::read_unvalidated_scene(detail::read_scene_text(path), path,
                                          std::filesystem::path(path).parent_path().string());
  });
}

SceneCheck check_scene_json(const std::string& text, const std::string& file,
                            const std::string& base_dir) {
  return check_loaded([&] { return detail::read_unvalidated_scene(text, file, base_dir); });
}

}  // namespace lightsolver
