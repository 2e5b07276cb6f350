// The process-wide phase recorder of lightsolver/timings.hpp.
#include "lightsolver/timings.hpp"

#include <time.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <mutex>

namespace lightsolver::timings {
namespace {

using Clock = std::chrono::steady_clock;

struct Recorder {
  std::atomic<bool> on{false};
  std::mutex mutex;
  Clock::time_point origin;
  double cpu_before_ms = 0.0, monotonic_ms = 0.0;
  std::vector<Phase> phases;
};

Recorder& recorder() {
  static Recorder r;
  return r;
}

thread_local int t_depth = 0;  // open scopes on this thread

double ms_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

double clock_ms(clockid_t id) {
  timespec t{};
  clock_gettime(id, &t);
  return 1e3 * double(t.tv_sec) + 1e-6 * double(t.tv_nsec);
}

void record(const char* name, int depth, Clock::time_point start, Clock::time_point end,
            bool beside = false) {
  Recorder& r = recorder();
  std::lock_guard<std::mutex> lock(r.mutex);
  r.phases.push_back({name, depth, ms_between(r.origin, start), ms_between(start, end), beside});
}

}  // namespace

void enable() {
  Recorder& r = recorder();
  std::lock_guard<std::mutex> lock(r.mutex);
  r.cpu_before_ms = clock_ms(CLOCK_PROCESS_CPUTIME_ID);
  r.monotonic_ms = clock_ms(CLOCK_MONOTONIC);
  r.origin = Clock::now();
  r.phases.clear();
  r.on.store(true, std::memory_order_relaxed);
}

bool enabled() { return recorder().on.load(std::memory_order_relaxed); }

void mark(const char* name) {
  if (!enabled()) return;
  const Clock::time_point now = Clock::now();
  record(name, t_depth, now, now);
}

std::vector<Phase> phases() {
  Recorder& r = recorder();
  std::lock_guard<std::mutex> lock(r.mutex);
  return r.phases;
}

double cpu_ms_before_enable() { return recorder().cpu_before_ms; }

double monotonic_ms_at_enable() { return recorder().monotonic_ms; }

Scope::Scope(const char* name) : name_(name), on_(enabled()) {
  if (!on_) return;
  ++t_depth;
  start_ = Clock::now();
}

Scope::Scope(const char* name, int depth) : name_(name), on_(enabled()) {
  if (!on_) return;
  saved_depth_ = t_depth;
  t_depth = depth + 1;
  start_ = Clock::now();
}

Scope::~Scope() {
  if (!on_) return;
  const Clock::time_point end = Clock::now();
  --t_depth;
  record(name_, t_depth, start_, end, saved_depth_ >= 0);
  if (saved_depth_ >= 0) t_depth = saved_depth_;
}

std::string format(const std::vector<Phase>& recorded) {
  std::vector<Phase> sorted = recorded;  // parents before their children
  std::stable_sort(sorted.begin(), sorted.end(), [](const Phase& a, const Phase& b) {
    return a.start_ms != b.start_ms ? a.start_ms < b.start_ms : a.depth < b.depth;
  });
  struct Line {
    Phase phase;
    int count;
    double end_ms;
  };
  std::vector<Line> lines;
  for (const Phase& p : sorted) {
    if (p.beside) continue;
    // The previous phase at this depth or above: a sibling of the same name is summed into it.
    auto sibling = std::find_if(lines.rbegin(), lines.rend(),
                                [&](const Line& l) { return l.phase.depth <= p.depth; });
    if (p.ms > 0.0 && sibling != lines.rend() && sibling->phase.depth == p.depth &&
        sibling->phase.name == p.name) {
      sibling->phase.ms += p.ms;
      sibling->count += 1;
      sibling->end_ms = p.start_ms + p.ms;
      continue;
    }
    lines.push_back({p, 1, p.start_ms + p.ms});
  }
  // A phase of another thread goes after the phases nested in its parent (the last one at the
  // depth above that started before it), so it does not split a parent from its children.
  for (const Phase& p : sorted) {
    if (!p.beside) continue;
    std::size_t at = lines.size(), parent = lines.size();
    for (std::size_t i = 0; i < lines.size(); ++i) {
      if (lines[i].phase.depth == p.depth - 1 && lines[i].phase.start_ms <= p.start_ms) parent = i;
    }
    if (parent < lines.size()) {
      at = parent + 1;
      while (at < lines.size() && lines[at].phase.depth > lines[parent].phase.depth) ++at;
    }
    lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(at), Line{p, 1, p.start_ms + p.ms});
  }
  std::string out = "timings (ms; the end column counts from main)\n";
  char row[160];
  for (const Line& l : lines) {
    std::string name = std::string(2 * l.phase.depth, ' ') + l.phase.name;
    if (l.count > 1) name += " (x" + std::to_string(l.count) + ")";
    if (l.phase.ms == 0.0) {  // a mark: only when it happened
      std::snprintf(row, sizeof row, "  %-40s %9s %9.2f\n", name.c_str(), "", l.end_ms);
    } else {
      std::snprintf(row, sizeof row, "  %-40s %9.2f %9.2f\n", name.c_str(), l.phase.ms, l.end_ms);
    }
    out += row;
  }
  return out;
}

}  // namespace lightsolver::timings
