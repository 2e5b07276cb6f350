// The type tables as front ends see them (lightsolver/type_tables.hpp): read from the rows.
#include "lightsolver/type_tables.hpp"

#include <span>

#include "types/luminaire_types.hpp"
#include "types/target_types.hpp"

namespace lightsolver {
namespace {

std::vector<std::string> strings(std::span<const char* const> list) {
  return {list.begin(), list.end()};
}

const char* glare_source_name(detail::GlareShape::Kind kind) {
  switch (kind) {
    case detail::GlareShape::Kind::LambertianArea:
      return "lambertian_area";
    case detail::GlareShape::Kind::PhotometricBody:
      return "photometric_body";
    case detail::GlareShape::Kind::None:
      break;
  }
  return "";
}

// The requirement keys of RequirementKey bits, in the scene file's spelling.
std::vector<std::string> requirement_names(unsigned bits) {
  constexpr std::pair<unsigned, const char*> kKeys[] = {{detail::kRequireEm, "em_lux"},
                                                        {detail::kRequireU0, "u0"},
                                                        {detail::kRequireEmin, "emin_lux"},
                                                        {detail::kRequireUd, "ud"},
                                                        {detail::kRequireUgr, "ugr_max"}};
  std::vector<std::string> out;
  for (const auto& [bit, key] : kKeys) {
    if (bits & bit) out.emplace_back(key);
  }
  return out;
}

}  // namespace

std::vector<LuminaireTypeInfo> luminaire_type_infos() {
  std::vector<LuminaireTypeInfo> out;
  for (const detail::LuminaireType& row : detail::luminaire_types()) {
    Luminaire scratch;  // the hooks that answer per type, not per luminaire, are asked with it
    scratch.type = row.type;
    const bool no_glare = row.glare_kind == detail::GlareShape::Kind::None;
    out.push_back({.name = row.name,
                   .keys = strings(row.keys),
                   .effect = row.effect,
                   .glare_source = glare_source_name(row.glare_kind),
                   .not_glare_because = no_glare ? row.glare(scratch).why_not : "",
                   .aimable = row.aim(scratch) != nullptr,
                   .placed = row.placed});
  }
  return out;
}

std::vector<TargetTypeInfo> target_type_infos() {
  std::vector<TargetTypeInfo> out;
  for (const detail::TargetType& row : detail::target_types()) {
    // Eyes per type: one for an observer; a grid of them counts its own (0 when empty).
    Target one_eye;
    one_eye.type = row.type;
    one_eye.positions = {{0, 0, 0}};
    one_eye.view_directions = {{1, 0, 0}};
    out.push_back({.name = row.name,
                   .keys = strings(row.keys),
                   .requirements = requirement_names(row.requirements),
                   .cells = row.cells,
                   .eyes = row.eyes(one_eye) > 0,
                   .tally = row.tally == detail::TallyKind::MeshBin ? "mesh_bin" : "grid_rows",
                   .result_fields = strings(row.result_fields)});
  }
  return out;
}

}  // namespace lightsolver
