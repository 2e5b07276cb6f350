#pragma once
/// \file type_tables.hpp
/// The solver's luminaire and target types as front ends see them (the workbench, the report,
/// `lightsolver.luminaire_types()` / `lightsolver.target_types()`): one entry per row of the
/// type tables (src/types/luminaire_types.cpp, target_types.cpp), read from the rows, so a front
/// end asks instead of keeping its own per-type branches.
#include <string>
#include <vector>

namespace lightsolver {

/// One luminaire type.
struct LuminaireTypeInfo {
  std::string name;               ///< "type" in the scene file
  std::vector<std::string> keys;  ///< its scene-file keys (every type also takes power_w, group)
  std::string effect;             ///< the effect it adds to Results::effects ("spot_emission")
  /// "lambertian_area", "photometric_body" or "" (not a glare source: see not_glare_because).
  std::string glare_source;
  std::string not_glare_because;  ///< why it is no glare source ("" when it is one)
  bool aimable = false;           ///< an aim design variable can turn it
  bool placed = false;            ///< an object in the room (spacing rules apply)
};

/// One target type.
struct TargetTypeInfo {
  std::string name;                        ///< "type" in the scene file
  std::vector<std::string> keys;           ///< its scene-file keys
  std::vector<std::string> requirements;   ///< the requirement keys it takes ("em_lux", ...)
  bool cells = false;                      ///< results have cells (nu x nv)
  bool eyes = false;                       ///< tallies eyes (reflected light only; glare)
  std::string tally;                       ///< "mesh_bin" or "grid_rows"
  std::vector<std::string> result_fields;  ///< results keys it adds to every target's
};

/// Every luminaire type, in the table's order.
std::vector<LuminaireTypeInfo> luminaire_type_infos();
/// Every target type, in the table's order.
std::vector<TargetTypeInfo> target_type_infos();

}  // namespace lightsolver
