#include "mfree/materials/finite_strain.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <string>
#include <vector>

#include "mfree/core/error.hpp"

namespace mfree {

namespace {

/// The error of an inverted F, apart from the check so that the check stays small.
template <int dim>
[[noreturn, gnu::cold, gnu::noinline]] void throw_inverted(const Tensor2<dim>& f, double j,
                                                           const char* model) {
  std::vector<std::string> rows;
  for (int i = 0; i < dim; ++i)
    rows.push_back(fmt::format("[{:.4g}]", fmt::join(f.row(i).begin(), f.row(i).end(), ", ")));
  throw NumericalError(
      fmt::format("{} material: J = det F = {:.4g} <= 0 (F = [{}]): the material is inverted", model, j,
                  fmt::join(rows, ", ")));
}

}  // namespace

template <int dim>
double checked_jacobian(const Tensor2<dim>& f, const char* model) {
  const double j = f.determinant();
  if (!(j > 0.0)) throw_inverted(f, j, model);
  return j;
}

template double checked_jacobian(const Tensor2<2>&, const char*);
template double checked_jacobian(const Tensor2<3>&, const char*);

}  // namespace mfree
