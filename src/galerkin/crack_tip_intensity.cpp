#include "mfree/galerkin/crack_tip_intensity.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "mfree/core/error.hpp"
#include "mfree/galerkin/galerkin_quadrature.hpp"
#include "mfree/quadrature/gauss_cells.hpp"

namespace mfree {

namespace {

double distance_to_segment(const Vec2& x, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double t = std::clamp((x - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (a + t * d - x).norm();
}

/// The largest outer radius the tip of crack c at end `end` allows: the length of its last
/// segment, and the distances to the rings' edges and to the other cracks.
double room_at_tip(const Domain& domain, std::size_t c, int end) {
  const Crack& crack = domain.cracks()[c];
  const std::size_t n = crack.points.size();
  // The straight run of segments behind the tip (a crack meshed into many elements) ends at
  // the first vertex off its line, a kink: the faces in the annulus must be straight.
  const auto point = [&](std::size_t k) -> const Vec2& {
    return end == 0 ? crack.points[k] : crack.points[n - 1 - k];
  };
  const Vec2& tip = point(0);
  const Vec2 direction = (point(1) - tip).normalized();
  std::size_t straight = 1;  // the segments 0 .. straight - 1 from the tip lie on one line
  while (straight + 1 < n) {
    const Vec2 d = point(straight + 1) - tip;
    if (std::abs(direction.x() * d.y() - direction.y() * d.x()) > 1e-12 * d.norm()) break;
    ++straight;
  }
  double room = (point(straight) - tip).norm();
  for (const BoundarySegment& s : domain.boundary()) {
    if (s.crack == static_cast<int>(c)) {
      const std::size_t from_tip =
          end == 0 ? static_cast<std::size_t>(s.edge) : n - 2 - static_cast<std::size_t>(s.edge);
      if (from_tip >= straight) room = std::min(room, distance_to_segment(tip, s.a, s.b));
      continue;
    }
    room = std::min(room, distance_to_segment(tip, s.a, s.b));
  }
  return room;
}

}  // namespace

std::vector<TipIntensity> crack_tip_intensities(const Domain& domain, const RKShapeFunctions<2>& trial,
                                                const Eigen::VectorXd& d, const LawAt& law_at, double h,
                                                const std::vector<std::string>& face_conditions) {
  std::vector<TipIntensity> out;
  if (domain.cracks().empty()) return out;
  const QuadratureRule<2> rule = gauss_cell_rule(domain, 0.5 * h, 4);
  for (std::size_t c = 0; c < domain.cracks().size(); ++c) {
    const Crack& crack = domain.cracks()[c];
    for (int end = 0; end < 2; ++end) {
      if (!crack.tip[end]) continue;
      const std::size_t n = crack.points.size();
      TipIntensity t;
      t.crack = crack.name;
      t.end = end;
      t.frame.position = end == 0 ? crack.points.front() : crack.points.back();
      t.frame.direction = (t.frame.position - (end == 0 ? crack.points[1] : crack.points[n - 2])).normalized();
      if (c < face_conditions.size() && !face_conditions[c].empty()) {
        t.loaded_by = face_conditions[c];
        const double nan = std::numeric_limits<double>::quiet_NaN();
        t.k = {nan, nan, nan};
        out.push_back(t);
        continue;
      }
      const double room = 0.9 * room_at_tip(domain, c, end);
      // A fixed share of the room once refined enough: the annulus then stays where u^h
      // converges, not a fixed number of spacings from the tip.
      t.outer_radius = std::min(room, std::max(4.0 * h, 0.5 * room));
      if (t.outer_radius < h)
        throw InputError(fmt::format("stress intensity at the tip ({}, {}) of crack '{}': the annulus of the interaction "
                                     "integral has {:.3g} of room (its straight last segment, other cracks and the "
                                     "boundary), less than the nodal spacing {}: refine the cloud",
                                     t.frame.position.x(), t.frame.position.y(), crack.name, room, h));
      const LinearElastic& material = law_at(t.frame.position);
      const DomainWeight weight{0.5 * t.outer_radius, t.outer_radius, WeightProfile::smooth};
      std::vector<Vec2> points;
      std::vector<double> weights;
      for (std::size_t p = 0; p < rule.size(); ++p)
        if ((rule.points[p] - t.frame.position).norm() < t.outer_radius) {
          points.push_back(rule.points[p]);
          weights.push_back(rule.weights[p]);
        }
      const GalerkinQuadrature<2> at = sample_shape_functions(trial, points, true);
      std::vector<Mat2> gradients(points.size());
      std::vector<Eigen::Vector3d> stresses(points.size());
      for (Index k = 0; k < at.size(); ++k) {
        Mat2 g = Mat2::Zero();
        for (Index e = at.row_begin(k); e < at.row_end(k); ++e) {
          const Index i = at.nodes[e];
          g += Vec2(d[2 * i], d[2 * i + 1]) * at.grad[e].transpose();
        }
        gradients[k] = g;
        const Mat2 s = material.stress(Mat2(Mat2::Identity() + g));
        stresses[k] = Eigen::Vector3d(s(0, 0), s(1, 1), s(0, 1));
      }
      t.k = interaction_integral(t.frame, material, weight, points, weights, gradients, stresses);
      out.push_back(std::move(t));
    }
  }
  return out;
}

}  // namespace mfree
