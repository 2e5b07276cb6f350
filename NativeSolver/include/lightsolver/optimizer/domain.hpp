#pragma once
/// \file domain.hpp
/// The discretised search domain of Sec. IV-B: each variable is cut into cells, a
/// configuration is one cell index per variable, and a cell stands for its centre value. A
/// luminaire position on a rectangle is two variables (k × m cells), an aiming angle one, a
/// flux choice one variable with explicit levels. Several luminaires simply add variables
/// (2 luminaires × (x, y) is a 4-D grid).

#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace lightsolver::optimizer {

/// One cell index per variable, in the order the variables were added.
using Configuration = std::vector<std::uint32_t>;

/// One search variable.
struct Variable {
  std::string name;         ///< e.g. "luminaires[0].position.x" — the scene integration decides
  double min = 0.0;         ///< range start (ignored when `levels` is set)
  double max = 1.0;         ///< range end (ignored when `levels` is set)
  std::uint32_t cells = 1;  ///< number of cells (ignored when `levels` is set)
  bool periodic = false;    ///< the last cell neighbours the first (a full turn of an angle)
  std::vector<double> levels;  ///< explicit values, one per cell (e.g. flux options), if set

  /// Number of cells.
  std::uint32_t size() const;
  /// Value a cell stands for: its centre min + (i + ½)(max − min)/cells, or levels[i].
  double value(std::uint32_t cell) const;
  /// Cell containing `v` (ranges: clamped into range; levels: the nearest level).
  std::uint32_t cell_of(double v) const;
};

/// Which cells are at distance 1 for the local search.
enum class Neighbourhood {
  kAxis,       ///< ±1 along one variable: 2·d neighbours (default; cheap in 4-D and up)
  kChebyshev,  ///< every cell whose indices all differ by at most 1: 3^d − 1 neighbours
};

/// A product of variables. Distances are Chebyshev (max over variables of the index
/// difference, wrapping around periodic variables).
class Domain {
 public:
  /// Adds a variable after checking it; throws std::invalid_argument naming it.
  Domain& add(Variable v);
  /// A range cut into `cells` equal cells.
  Domain& add_range(std::string name, double min, double max, std::uint32_t cells,
                    bool periodic = false);
  /// A position on an axis-aligned rectangle: variables `name.x` (k cells) and `name.y`
  /// (m cells) in the rectangle's own coordinates; the scene integration maps them to 3-D.
  Domain& add_rectangle(const std::string& name, double x0, double x1, std::uint32_t k, double y0,
                        double y1, std::uint32_t m);
  /// An angle in degrees; periodic when the range spans a full turn.
  Domain& add_angle(std::string name, double min_deg, double max_deg, std::uint32_t cells);
  /// A choice among explicit values (e.g. luminous flux options in lumens).
  Domain& add_levels(std::string name, std::vector<double> levels);

  const std::vector<Variable>& variables() const { return vars_; }
  std::size_t dimensions() const { return vars_.size(); }
  /// Total number of configurations (throws if it would exceed 2^63).
  std::uint64_t cell_count() const { return count_; }

  bool contains(const Configuration& c) const;
  /// Mixed-radix index in [0, cell_count()), first variable fastest. Throws if !contains(c).
  std::uint64_t index(const Configuration& c) const;
  Configuration configuration(std::uint64_t index) const;
  /// Centre values of a configuration's cells.
  std::vector<double> values(const Configuration& c) const;
  /// Configuration whose cells contain the given values.
  Configuration cell_of(const std::vector<double>& values) const;

  /// Chebyshev distance between two configurations.
  std::uint32_t distance(const Configuration& a, const Configuration& b) const;
  /// Configurations at distance 1, in a fixed order. kChebyshev needs d <= 12.
  std::vector<Configuration> neighbours(const Configuration& c, Neighbourhood kind) const;
  /// A random configuration, uniformly over all cells.
  Configuration random(std::mt19937_64& rng) const;
  /// VNS shake: a random configuration at distance exactly min(k, the largest distance
  /// reachable from c). One variable, chosen at random among those that can move that far,
  /// moves by ±k; every other variable joins with probability ½ and moves by a uniform offset
  /// in [−k, k]. Returns c itself only when the domain has a single cell.
  Configuration shake(const Configuration& c, std::uint32_t k, std::mt19937_64& rng) const;

 private:
  std::uint32_t reach(std::size_t i, std::uint32_t cell, std::uint32_t k) const;
  std::uint32_t step(std::size_t i, std::uint32_t cell, std::int64_t offset) const;

  std::vector<Variable> vars_;
  std::uint64_t count_ = 1;
};

/// Uniform integer in [0, n) by rejection: portable across standard libraries, unlike
/// std::uniform_int_distribution, so a seed means the same search everywhere. n > 0.
std::uint64_t uniform_below(std::mt19937_64& rng, std::uint64_t n);

}  // namespace lightsolver::optimizer
