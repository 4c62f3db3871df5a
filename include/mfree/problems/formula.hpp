#pragma once
// Values given as formulas in a scene: scalar expressions in the coordinates and time,
// parsed once by muParser (the parser behind deal.II's FunctionParser) and evaluated as
// often as the solver asks.
//
// Variables: x, y (current or small-strain coordinates), X, Y (reference coordinates; in
// every solver here a formula is evaluated at reference positions, so x = X and y = Y) and
// t (time; the load factor of a static Newton solve is not time: loads are scaled by it);
// a formula of a solid (dimension 3) also has z and Z, which a plane formula refuses.
// Constants: pi, e, and the scene's [constants] table. Functions and operators: muParser's
// (sin, cos, tan, asin, acos, atan, sinh, cosh, tanh, exp, log, ln, log10, sqrt, abs, sign,
// min, max, sum, avg, ^, ?:, comparison and logical operators).
//
// Errors: a formula that does not parse, or names an unknown variable, is an InputError
// naming the formula's key, the position in the formula and what is wrong; a value that is
// NaN or infinite at some point is an InputError (the scene's formula is at fault) naming the
// key, the point and the time.
// Evaluation is thread-safe (one parser per OpenMP thread).

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "mfree/core/types.hpp"

namespace mfree {

/// Named constants a formula may use, by name.
using Constants = std::map<std::string, double>;

class Formula {
 public:
  /// Parses `expression`; `key` names it in every message (e.g. "scene.toml: key 'exact.u[0]'").
  /// Throws InputError for a syntax error, an unknown variable, or a constant name that is
  /// not a valid identifier or shadows a variable. `dimension` (2 or 3) sets the variables.
  Formula(const std::string& expression, const Constants& constants, std::string key, int dimension = 2);
  /// The constant c (no parsing).
  static Formula constant(double c, std::string key);
  Formula(const Formula&);
  Formula(Formula&&) noexcept;
  Formula& operator=(const Formula&);
  Formula& operator=(Formula&&) noexcept;
  ~Formula();

  /// The value at point x and time t; throws InputError when it is NaN or infinite.
  [[nodiscard]] double operator()(const Vec2& x, double t = 0.0) const;
  /// The value at a point in space (a formula of dimension 3).
  [[nodiscard]] double operator()(const Vec3& x, double t = 0.0) const;
  /// Values at many points at one time (out resized to points.size()).
  void evaluate(const std::vector<Vec2>& points, double t, std::vector<double>& out) const;

  [[nodiscard]] const std::string& expression() const;
  [[nodiscard]] const std::string& key() const;
  /// True when the formula uses t.
  [[nodiscard]] bool depends_on_time() const;
  /// True when the formula uses x, y, X or Y (or z, Z).
  [[nodiscard]] bool depends_on_space() const;
  /// True when the formula uses none of its variables.
  [[nodiscard]] bool is_constant() const;

 private:
  struct Impl;
  std::shared_ptr<const Impl> impl_;  // immutable once built; copies share it
};

/// Two formulas: a vector field (a displacement, traction, body force or velocity).
struct VectorFormula {
  Formula x, y;
  [[nodiscard]] Vec2 operator()(const Vec2& p, double t = 0.0) const { return {x(p, t), y(p, t)}; }
  [[nodiscard]] bool depends_on_time() const { return x.depends_on_time() || y.depends_on_time(); }
};

/// Three formulas of dimension 3: a vector field in space.
struct SpaceVectorFormula {
  Formula x, y, z;
  [[nodiscard]] Vec3 operator()(const Vec3& p, double t = 0.0) const { return {x(p, t), y(p, t), z(p, t)}; }
  [[nodiscard]] bool depends_on_time() const {
    return x.depends_on_time() || y.depends_on_time() || z.depends_on_time();
  }
};

}  // namespace mfree
