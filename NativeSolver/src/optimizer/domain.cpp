#include "lightsolver/optimizer/domain.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <unordered_set>

namespace lightsolver::optimizer {

namespace {

[[noreturn]] void fail(const std::string& var, const std::string& what) {
  throw std::invalid_argument("optimizer variable '" + var + "': " + what);
}

void check_variable(const Variable& v, const std::vector<Variable>& existing) {
  if (v.name.empty()) fail(v.name, "needs a name");
  for (const Variable& e : existing)
    if (e.name == v.name) fail(v.name, "name used twice");
  if (!v.levels.empty()) {
    for (double x : v.levels)
      if (!std::isfinite(x)) fail(v.name, "levels must be finite");
    if (v.levels.size() > std::numeric_limits<std::uint32_t>::max()) fail(v.name, "too many");
    return;
  }
  if (!std::isfinite(v.min) || !std::isfinite(v.max) || !(v.min < v.max))
    fail(v.name, "needs finite min < max");
  if (v.cells < 1) fail(v.name, "needs at least one cell");
}

}  // namespace

std::uint64_t uniform_below(std::mt19937_64& rng, std::uint64_t n) {
  // Reject the top partial block of 2^64 so every residue is equally likely.
  const std::uint64_t limit =
      std::numeric_limits<std::uint64_t>::max() - std::numeric_limits<std::uint64_t>::max() % n;
  std::uint64_t r = rng();
  while (r >= limit) r = rng();
  return r % n;
}

std::uint32_t Variable::size() const {
  return levels.empty() ? cells : static_cast<std::uint32_t>(levels.size());
}

double Variable::value(std::uint32_t cell) const {
  if (!levels.empty()) return levels.at(cell);
  if (cell >= cells) throw std::out_of_range("Variable::value: cell out of range");
  return min + (cell + 0.5) * (max - min) / cells;
}

std::uint32_t Variable::cell_of(double v) const {
  if (!levels.empty()) {
    std::uint32_t best = 0;
    for (std::uint32_t i = 1; i < levels.size(); ++i)
      if (std::abs(levels[i] - v) < std::abs(levels[best] - v)) best = i;
    return best;
  }
  const double span = max - min;
  if (periodic) v = min + std::fmod(std::fmod(v - min, span) + span, span);
  const double t = std::floor((v - min) / span * cells);
  return static_cast<std::uint32_t>(std::clamp(t, 0.0, static_cast<double>(cells - 1)));
}

Domain& Domain::add(Variable v) {
  check_variable(v, vars_);
  const std::uint64_t n = v.size();
  if (count_ > (std::uint64_t{1} << 63) / n) fail(v.name, "the grid has more than 2^63 cells");
  count_ *= n;
  vars_.push_back(std::move(v));
  return *this;
}

Domain& Domain::add_range(std::string name, double min, double max, std::uint32_t cells,
                          bool periodic) {
  Variable v;
  v.name = std::move(name);
  v.min = min;
  v.max = max;
  v.cells = cells;
  v.periodic = periodic;
  return add(std::move(v));
}

Domain& Domain::add_rectangle(const std::string& name, double x0, double x1, std::uint32_t k,
                              double y0, double y1, std::uint32_t m) {
  add_range(name + ".x", x0, x1, k);
  return add_range(name + ".y", y0, y1, m);
}

Domain& Domain::add_angle(std::string name, double min_deg, double max_deg, std::uint32_t cells) {
  const double span = max_deg - min_deg;
  if (span > 360.0 + 1e-9) fail(name, "an angle range spans at most 360 degrees");
  return add_range(std::move(name), min_deg, max_deg, cells, span >= 360.0 - 1e-9);
}

Domain& Domain::add_levels(std::string name, std::vector<double> levels) {
  if (levels.empty()) fail(name, "needs at least one level");
  Variable v;
  v.name = std::move(name);
  v.levels = std::move(levels);
  return add(std::move(v));
}

bool Domain::contains(const Configuration& c) const {
  if (c.size() != vars_.size()) return false;
  for (std::size_t i = 0; i < c.size(); ++i)
    if (c[i] >= vars_[i].size()) return false;
  return true;
}

std::uint64_t Domain::index(const Configuration& c) const {
  if (!contains(c)) throw std::out_of_range("Domain::index: configuration outside the grid");
  std::uint64_t idx = 0;
  for (std::size_t i = vars_.size(); i-- > 0;) idx = idx * vars_[i].size() + c[i];
  return idx;
}

Configuration Domain::configuration(std::uint64_t index) const {
  if (index >= count_) throw std::out_of_range("Domain::configuration: index out of range");
  Configuration c(vars_.size());
  for (std::size_t i = 0; i < vars_.size(); ++i) {
    c[i] = static_cast<std::uint32_t>(index % vars_[i].size());
    index /= vars_[i].size();
  }
  return c;
}

std::vector<double> Domain::values(const Configuration& c) const {
  if (!contains(c)) throw std::out_of_range("Domain::values: configuration outside the grid");
  std::vector<double> v(c.size());
  for (std::size_t i = 0; i < c.size(); ++i) v[i] = vars_[i].value(c[i]);
  return v;
}

Configuration Domain::cell_of(const std::vector<double>& values) const {
  if (values.size() != vars_.size()) throw std::invalid_argument("Domain::cell_of: wrong size");
  Configuration c(values.size());
  for (std::size_t i = 0; i < c.size(); ++i) c[i] = vars_[i].cell_of(values[i]);
  return c;
}

std::uint32_t Domain::distance(const Configuration& a, const Configuration& b) const {
  if (!contains(a) || !contains(b)) throw std::out_of_range("Domain::distance: outside the grid");
  std::uint32_t d = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    std::uint32_t di = a[i] > b[i] ? a[i] - b[i] : b[i] - a[i];
    if (vars_[i].periodic) di = std::min(di, vars_[i].size() - di);
    d = std::max(d, di);
  }
  return d;
}

std::uint32_t Domain::reach(std::size_t i, std::uint32_t cell, std::uint32_t k) const {
  const std::uint32_t n = vars_[i].size();
  if (vars_[i].periodic) return std::min(k, n / 2);
  return std::min(k, std::max(cell, n - 1 - cell));
}

std::uint32_t Domain::step(std::size_t i, std::uint32_t cell, std::int64_t offset) const {
  const std::int64_t n = vars_[i].size();
  const std::int64_t t = static_cast<std::int64_t>(cell) + offset;
  if (vars_[i].periodic) return static_cast<std::uint32_t>(((t % n) + n) % n);
  return static_cast<std::uint32_t>(t);  // callers only ask for in-range steps
}

std::vector<Configuration> Domain::neighbours(const Configuration& c, Neighbourhood kind) const {
  if (!contains(c)) throw std::out_of_range("Domain::neighbours: outside the grid");
  const std::size_t d = vars_.size();
  if (kind == Neighbourhood::kChebyshev && d > 12)
    throw std::invalid_argument("Domain::neighbours: Chebyshev neighbourhood needs d <= 12");
  std::vector<std::vector<std::int64_t>> offsets;
  if (kind == Neighbourhood::kAxis) {
    for (std::size_t i = 0; i < d; ++i)
      for (std::int64_t s : {-1, 1}) {
        std::vector<std::int64_t> o(d, 0);
        o[i] = s;
        offsets.push_back(std::move(o));
      }
  } else {
    std::uint64_t total = 1;
    for (std::size_t i = 0; i < d; ++i) total *= 3;
    for (std::uint64_t m = 0; m < total; ++m) {
      std::vector<std::int64_t> o(d);
      std::uint64_t r = m;
      for (std::size_t i = 0; i < d; ++i, r /= 3) o[i] = static_cast<std::int64_t>(r % 3) - 1;
      offsets.push_back(std::move(o));
    }
  }
  std::vector<Configuration> out;
  std::unordered_set<std::uint64_t> seen{index(c)};  // periodic wrap can repeat cells
  for (const auto& o : offsets) {
    Configuration n = c;
    bool ok = true;
    for (std::size_t i = 0; i < d && ok; ++i) {
      const std::int64_t t = static_cast<std::int64_t>(c[i]) + o[i];
      ok = vars_[i].periodic || (t >= 0 && t < static_cast<std::int64_t>(vars_[i].size()));
      if (ok) n[i] = step(i, c[i], o[i]);
    }
    if (ok && seen.insert(index(n)).second) out.push_back(std::move(n));
  }
  return out;
}

Configuration Domain::random(std::mt19937_64& rng) const {
  return configuration(uniform_below(rng, count_));
}

Configuration Domain::shake(const Configuration& c, std::uint32_t k, std::mt19937_64& rng) const {
  if (!contains(c)) throw std::out_of_range("Domain::shake: outside the grid");
  std::uint32_t kt = 0;
  for (std::size_t i = 0; i < c.size(); ++i) kt = std::max(kt, reach(i, c[i], k));
  if (kt == 0) return c;
  std::vector<std::size_t> leads;
  for (std::size_t i = 0; i < c.size(); ++i)
    if (reach(i, c[i], k) == kt) leads.push_back(i);
  const std::size_t lead = leads[uniform_below(rng, leads.size())];
  Configuration out = c;
  for (std::size_t i = 0; i < c.size(); ++i) {
    const bool per = vars_[i].periodic;
    const std::int64_t down = per ? kt : std::min<std::int64_t>(kt, c[i]);
    const std::int64_t up = per ? kt : std::min<std::int64_t>(kt, vars_[i].size() - 1 - c[i]);
    if (i == lead) {
      // Move the lead variable by exactly kt, in a direction that stays on the grid.
      const bool can_down = down == kt, can_up = up == kt;
      const bool go_up = can_up && (!can_down || (rng() & 1u));
      out[i] = step(i, c[i], go_up ? kt : -static_cast<std::int64_t>(kt));
    } else if (rng() & 1u) {
      const auto offset = static_cast<std::int64_t>(uniform_below(rng, down + up + 1)) - down;
      out[i] = step(i, c[i], offset);
    }
  }
  return out;
}

}  // namespace lightsolver::optimizer
