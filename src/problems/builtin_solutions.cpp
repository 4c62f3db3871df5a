#include "mfree/problems/builtin_solutions.hpp"

#include <fmt/format.h>

#include <cmath>

#include "mfree/core/error.hpp"
#include "mfree/problems/axis_aligned_vibration.hpp"
#include "mfree/problems/polynomial_fields.hpp"
#include "mfree/problems/timoshenko_beam.hpp"

namespace mfree {

namespace {

// SPEC section 4: the beam's axis is y = 0 from x = 0, so the body is [0, L] x [-D/2, D/2].
ExactElasticity beam(const SolutionValues& v, const SolutionSetting& s) {
  const Box& b = s.body;
  if (std::abs(b.lo.x()) > 1e-12 * b.size().x() || std::abs(b.lo.y() + b.hi.y()) > 1e-12 * b.size().y())
    throw InputError("the timoshenko_beam solution needs the domain [0, L] x [-D/2, D/2]");
  return timoshenko_beam(b.size().x(), b.size().y(), v.numbers.at("load"), s.material);
}

ExactElasticity linear(const SolutionValues& v, const SolutionSetting& s) {
  return linear_field(v.vectors.at("offset"), v.matrices.at("gradient"), s.material);
}

ExactElasticity quadratic(const SolutionValues& v, const SolutionSetting& s) {
  return quadratic_field(v.vectors.at("offset"), v.matrices.at("gradient"), v.matrices.at("hessian_x"),
                         v.matrices.at("hessian_y"), s.material);
}

ExactMotion<2> vibration(const SolutionValues& v, const SolutionSetting& s) {
  const Box& b = s.body;
  if (b.lo.norm() > 1e-12 * b.size().norm() || std::abs(b.size().x() - b.size().y()) > 1e-12 * b.size().x())
    throw InputError("the vibration solution needs the square domain [0, L] x [0, L]");
  if (!s.neo_hookean) throw InputError("the vibration solution needs the material model \"neo_hookean\"");
  if (!(s.density > 0.0)) throw InputError("the vibration solution needs the material's density");
  const AxisAlignedVibration a{v.numbers.at("amplitude"), b.size().x(), s.material.youngs_modulus,
                               s.material.poisson_ratio, s.density};
  a.check_amplitude();
  return a.motion<2>();
}

}  // namespace

const NameTable<BuiltinSolution>& builtin_solutions() {
  using K = ParameterKind;
  static const NameTable<BuiltinSolution> table{
      {"timoshenko_beam", {{{"load", K::number}}, beam, {}}},
      {"linear", {{{"offset", K::vector}, {"gradient", K::matrix}}, linear, {}}},
      {"quadratic",
       {{{"offset", K::vector},
         {"gradient", K::matrix},
         {"hessian_x", K::symmetric_matrix},
         {"hessian_y", K::symmetric_matrix}},
        quadratic,
        {}}},
      {"vibration", {{{"amplitude", K::number}}, {}, vibration}},
  };
  return table;
}

}  // namespace mfree
