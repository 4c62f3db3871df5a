#include "mfree/quadrature/rule_on_cracks.hpp"

#include "mfree/geometry/crack_faces.hpp"

namespace mfree {

QuadratureRule<2> split_rule_on_cracks(const Domain& domain, QuadratureRule<2> rule, double h) {
  if (domain.cracks().empty()) return rule;
  std::vector<Index> origin;
  std::vector<Vec2> points = split_on_cracks(domain, rule.points, h, &origin);
  std::vector<double> weights(points.size());
  for (std::size_t p = 0; p < points.size(); ++p) {
    const bool split =
        (p > 0 && origin[p - 1] == origin[p]) || (p + 1 < points.size() && origin[p + 1] == origin[p]);
    weights[p] = rule.weights[origin[p]] * (split ? 0.5 : 1.0);
  }
  return QuadratureRule<2>{std::move(points), std::move(weights)};
}

}  // namespace mfree
