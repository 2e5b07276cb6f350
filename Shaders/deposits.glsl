// Per-path deposit counts, so each bin receives this path's total c and c^2 (the variance
// estimate needs whole-path totals). A path keeps at most kMaxDeposits distinct bins in
// registers. To stay exact for paths that touch more, a pass keeps the kMaxDeposits SMALLEST bins
// above `dep_floor`: a bin refused or evicted is larger than every kept bin, and the largest kept
// bin only decreases, so it can never come back with a partial count. After the pass every kept
// count is complete; if anything was refused the path is replayed (same random stream, same
// code, hence the same path) with dep_floor = the largest bin flushed. Paths within the budget,
// nearly all of them, take one pass.
#ifndef LIGHTSOLVER_DEPOSITS_GLSL
#define LIGHTSOLVER_DEPOSITS_GLSL

#include "shared/grids.h"

const uint kMaxDeposits = 16u;

uint dep_key[kMaxDeposits];    // bin + 1, so that dep_floor = 0 admits every bin
uint dep_count[kMaxDeposits];
uint dep_size;
uint dep_floor;
bool dep_refused;

void deposits_begin(uint floor_key) {
  dep_size = 0u;
  dep_floor = floor_key;
  dep_refused = false;
}

void deposit(uint bin) {
  const uint key = bin + 1u;
  if (key <= dep_floor) return;  // flushed by an earlier pass
  uint largest = 0u;
  for (uint i = 0u; i < dep_size; ++i) {
    if (dep_key[i] == key) {
      ++dep_count[i];
      return;
    }
    if (dep_key[i] > dep_key[largest]) largest = i;
  }
  if (dep_size < kMaxDeposits) {
    dep_key[dep_size] = key;
    dep_count[dep_size] = 1u;
    ++dep_size;
    return;
  }
  dep_refused = true;
  if (key < dep_key[largest]) {  // evict the largest: it is replayed in a later pass
    dep_key[largest] = key;
    dep_count[largest] = 1u;
  }
}

// Adds this pass's complete counts; returns the floor for the next pass, or 0 when done. Fully
// unrolled: with no loop left, lavapipe's loop limit (trace.comp) cannot stop it half-way.
uint deposits_flush() {
  uint largest = 0u;
  [[unroll]] for (uint i = 0u; i < kMaxDeposits; ++i) {
    if (i < dep_size) {
      const uint bin = pc.tally_offset + dep_key[i] - 1u;  // this group's tallies
      const uint64_t c = uint64_t(dep_count[i]);
      atomicAdd(tallies[2u * bin], c);
      atomicAdd(tallies[2u * bin + 1u], c * c);
      largest = max(largest, dep_key[i]);
    }
  }
  return dep_refused ? largest : 0u;
}

// Virtual grids crossed from the front by o + t d, 0 <= t <= t_max (shared/grids.h, the text
// model/path_deposits.hpp includes too). `bounce`: reflections before this segment;
// indirect-only grids (observers) skip bounce 0, and so does every grid when pc.first_bounce is 1
// (the group's direct light is by next-event estimation) but those whose direct light went back
// to the photons (kGridDirectByPhotons), as cross_grids in path_deposits.hpp; a connected group's
// reflected segments count crossings nearer than connect_r0 only (the connection counts the rest).
void cross_grids(vec3 o, vec3 d, float t_max, uint bounce) {
  const bool by_shadow_rays = bounce < pc.first_bounce;  // where not given back to photons
  const float t_end = grid_reach(t_max);
  const bool capped = pc.connected != 0u && bounce >= 1u;  // near crossings only (connected)
  for (uint k = 0u; k < pc.grid_count; ++k) {
    const GridGpu g = grids[k];
    if (bounce == 0u && ((g.flags & kGridIndirectOnly) != 0u ||
                         (by_shadow_rays && (g.flags & kGridDirectByPhotons) == 0u))) {
      continue;
    }
    const float t_grid = capped && g.connect_r0 > 0.0 ? min(t_end, g.connect_r0) : t_end;
    uint cell;
    if (!grid_crossing(o, d, t_grid, g.corner, g.normal, g.du, g.dv, g.nu, g.nv, cell)) continue;
    deposit(g.bin);
    deposit(g.bin + 1u + cell);
  }
}

#endif
