#pragma once
/// Where a process's time goes before its first photon (`lightsolver run --timings`): a
/// process-wide recorder of named phases, off by default. While off, a phase costs one relaxed
/// atomic load; while on, two clock reads and a short locked append.
#include <chrono>
#include <string>
#include <vector>

namespace lightsolver::timings {

/// One recorded phase: `depth` is its nesting on the thread that recorded it (0 = outermost);
/// times are milliseconds of the steady clock since enable().
struct Phase {
  std::string name;
  int depth = 0;
  double start_ms = 0.0;
  double ms = 0.0;      // 0 for a mark (a point in time)
  bool beside = false;  // on a thread of its own beside the one that records the others
};

/// Starts recording (again: an earlier record is dropped); the origin of every time is now.
void enable();

/// Whether phases are being recorded.
bool enabled();

/// A point in time, e.g. "ready to trace".
void mark(const char* name);

/// The phases recorded so far, in the order they ended (a mark: when it was made).
std::vector<Phase> phases();

/// The process's CPU time (user + system, ms) when enable() was called: in `main`, what the
/// process spent before it (exec, loading shared libraries, static initialisers).
double cpu_ms_before_enable();

/// CLOCK_MONOTONIC at enable(), in ms: a parent that reads the same clock before it starts the
/// process (Python's time.monotonic()) gets the time from its start to main.
double monotonic_ms_at_enable();

/// The phase's time from construction to destruction, recorded while enabled.
class Scope {
 public:
  explicit Scope(const char* name);
  /// On a thread of its own: at `depth`, as if nested there (the thread's own nesting restarts).
  Scope(const char* name, int depth);
  ~Scope();
  Scope(const Scope&) = delete;
  Scope& operator=(const Scope&) = delete;

 private:
  const char* name_;
  bool on_;
  int saved_depth_ = -1;  // the thread's nesting before a Scope with a given depth
  std::chrono::steady_clock::time_point start_;
};

/// The record as text, one phase a line, nested phases indented; phases of the same name
/// recorded one after another under the same parent are summed ("read mesh file (x3)").
std::string format(const std::vector<Phase>& phases);

}  // namespace lightsolver::timings
