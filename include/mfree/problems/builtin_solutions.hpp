#pragma once
// The exact solutions built into mfree, in one table. A scene's [exact] solution = "name"
// finds its entry here, reads the parameters the entry lists (by kind: a number, a vector
// [a, b], a matrix [[a, b], [c, d]]), and has the entry build the solution on the scene's
// body and material. A new built-in problem is one file in problems/ and one line here.
//
// An entry is either static (small-strain theory, errors by galerkin/exact_elasticity) or a
// motion with the body force that makes it exact (errors by galerkin/motion_errors and
// mpm/particle_errors; the initial state is the motion at t = 0).

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "mfree/core/exact_motion.hpp"
#include "mfree/core/name_table.hpp"
#include "mfree/core/types.hpp"
#include "mfree/galerkin/exact_elasticity.hpp"
#include "mfree/materials/linear_elastic.hpp"

namespace mfree {

enum class ParameterKind { number, vector, matrix, symmetric_matrix };

struct SolutionParameter {
  std::string name;
  ParameterKind kind;
};

/// The values of an entry's parameters, by name.
struct SolutionValues {
  std::map<std::string, double> numbers;
  std::map<std::string, Vec2> vectors;
  std::map<std::string, Mat2> matrices;  ///< matrix and symmetric_matrix
};

/// What a solution is posed on.
struct SolutionSetting {
  Box body;                  ///< the body's bounding box (reference configuration)
  LinearElastic material;    ///< E, nu and the plane model (of the law or of its linearisation)
  bool neo_hookean = false;  ///< the law is the compressible Neo-Hookean one
  double density = 0.0;      ///< rho0; 0 when not given
};

/// A built-in solution. The builders throw InputError, saying what the solution needs, for a
/// setting it does not fit (a domain of another shape, another material law).
struct BuiltinSolution {
  std::vector<SolutionParameter> parameters;
  std::function<ExactElasticity(const SolutionValues&, const SolutionSetting&)> statics;  ///< or empty
  std::function<ExactMotion<2>(const SolutionValues&, const SolutionSetting&)> motion;    ///< or empty
};

/// timoshenko_beam, linear, quadratic (static); vibration (motion).
const NameTable<BuiltinSolution>& builtin_solutions();

}  // namespace mfree
