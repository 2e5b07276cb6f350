#pragma once
// What differs between two runs of the same scene with the same options, cleared so that their
// results can be compared bit for bit: the timing, and the provenance's thread count, times,
// host and command (docs/scene-format.md, "Provenance").
#include "lightsolver/solver.hpp"

namespace lightsolver::test {

inline Results without_run_facts(Results r) {
  r.seconds = 0;
  if (r.provenance) {
    r.provenance->threads = 0;
    r.provenance->started_utc = r.provenance->finished_utc = "";
    r.provenance->host = r.provenance->command = "";
  }
  return r;
}

}  // namespace lightsolver::test
