#pragma once
// Ctrl-C in the CLI: while an InterruptScope lives, SIGINT sets one flag that the work's `cancel`
// points to (a run, a cost table, a study, a search stops cleanly and writes what it has);
// outside it, SIGINT ends the process as usual. One flag and one handler for every command.
#include <atomic>
#include <csignal>

namespace lightsolver::cli {

/// True once Ctrl-C was pressed inside the current (or last) InterruptScope.
inline std::atomic<bool>& interrupted() {
  static std::atomic<bool> flag{false};
  return flag;
}

/// Catches SIGINT into interrupted() (cleared at the start) until it goes out of scope.
class InterruptScope {
 public:
  InterruptScope() {
    interrupted().store(false);  // the flag exists before the handler can run
    std::signal(SIGINT, [](int) { interrupted().store(true); });
  }
  ~InterruptScope() { std::signal(SIGINT, SIG_DFL); }
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;
};

}  // namespace lightsolver::cli
