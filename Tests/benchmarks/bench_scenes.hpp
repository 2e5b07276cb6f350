#pragma once
// Procedural benchmark scenes: a Cornell box, and a room full of tessellated spheres (~1M
// triangles) standing in for a detailed BIM model.

#include <cmath>
#include <numbers>

#include "../native/core/scene_builders.hpp"

namespace lightsolver::bench {

using test::add_material;
using test::room_mesh;

// Poles make zero-area triangles; drop them here so the scene needs no warnings.
inline void drop_degenerates(Mesh& m) {
  std::erase_if(m.triangles, [&](const glm::u32vec3& t) {
    return glm::length(glm::cross(m.vertices[t[1]] - m.vertices[t[0]],
                                  m.vertices[t[2]] - m.vertices[t[0]])) < 1e-12;
  });
}

// UV sphere with outward faces, `rings` x `segments` quads.
inline Mesh sphere_mesh(const std::string& name, int material, glm::dvec3 c, double r, int rings,
                        int segments) {
  Mesh m;
  m.name = name;
  m.material = material;
  for (int i = 0; i <= rings; ++i) {
    const double th = std::numbers::pi * i / rings;
    for (int j = 0; j < segments; ++j) {
      const double ph = 2 * std::numbers::pi * j / segments;
      m.vertices.push_back(c + r * glm::dvec3(std::sin(th) * std::cos(ph),
                                              std::sin(th) * std::sin(ph), std::cos(th)));
    }
  }
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < segments; ++j) {
      const auto a = std::uint32_t(i * segments + j),
                 b = std::uint32_t(i * segments + (j + 1) % segments);
      const auto c2 = a + segments, d = b + segments;
      m.triangles.push_back({a, c2, d});
      m.triangles.push_back({a, d, b});
    }
  }
  drop_degenerates(m);
  return m;
}

inline Luminaire ceiling_panel(glm::dvec3 corner, double size, double flux) {
  Luminaire l;
  l.name = "panel";
  l.type = Luminaire::Type::Area;
  l.corner = corner;
  l.edge1 = {0, size, 0};
  l.edge2 = {size, 0, 0};
  l.flux_lm = flux;
  return l;
}

// Cornell box: 5.5 m room (white 0.75 ceiling/floor/back, red and green side walls as grey
// reflectances), two boxes, a ceiling light; floor target and a workplane grid.
inline Scene cornell_box() {
  Scene s;
  add_material(s, "white", Material::Type::Diffuse, 0.75);
  add_material(s, "block", Material::Type::Diffuse, 0.6);
  s.meshes.push_back(room_mesh("room", 0, {0, 0, 0}, {5.5, 5.5, 5.5}, 4));
  s.meshes.push_back(test::solid_box_mesh("short block", 1, {1, 1, 0}, {2.6, 2.6, 1.6}, 2));
  s.meshes.push_back(test::solid_box_mesh("tall block", 1, {3, 3, 0}, {4.6, 4.6, 3.3}, 2));
  s.luminaires.push_back(ceiling_panel({2.2, 2.2, 5.5}, 1.1, 10'000));
  s.targets.push_back(test::surface("room", 0));
  s.targets.push_back(test::grid("workplane", {0.5, 0.5, 0.8}, {4.5, 0, 0}, {0, 4.5, 0}, 10, 10));
  validate(s);
  return s;
}

// A 20 x 20 x 4 m hall with 8 x 8 spheres of 250 x 32 quads each: ~1.02 M triangles.
inline Scene million_triangles() {
  Scene s;
  add_material(s, "wall", Material::Type::Diffuse, 0.6);
  add_material(s, "sphere", Material::Type::Diffuse, 0.5);
  s.meshes.push_back(room_mesh("hall", 0, {0, 0, 0}, {20, 20, 4}, 8));
  for (int i = 0; i < 8; ++i) {
    for (int j = 0; j < 8; ++j) {
      const std::string name = "sphere " + std::to_string(i) + "," + std::to_string(j);
      s.meshes.push_back(sphere_mesh(name, 1, {1.25 + 2.5 * i, 1.25 + 2.5 * j, 1.0}, 0.8, 250, 32));
    }
  }
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      s.luminaires.push_back(ceiling_panel({2 + 5.0 * i, 2 + 5.0 * j, 4}, 0.6, 4000));
    }
  }
  s.targets.push_back(test::grid("workplane", {0.5, 0.5, 0.8}, {19, 0, 0}, {0, 19, 0}, 20, 20));
  validate(s);
  return s;
}

}  // namespace lightsolver::bench
