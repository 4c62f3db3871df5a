#include "mfree/mpm/mls_reconstruction.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace mfree {

MLSReconstruction::MLSReconstruction(const Grid& grid, const ParticleBasis& basis, RKOrder order, double support)
    : grid_(grid), basis_(basis) {
  omega_ = 0.25 * grid.spacing() * grid.spacing();
  settings_.order = order;
  settings_.window = Window::quadratic_spline;
  settings_.support = SupportShape::tensor;
  settings_.radius = support * grid.spacing();
}

void MLSReconstruction::update(const std::vector<Vec2>& positions) {
  const double h = grid_.spacing();
  const int nx = grid_.cells_x(), ny = grid_.cells_y();
  std::vector<unsigned char> active(static_cast<std::size_t>(nx) * ny, 0);
  for (const Vec2& x : positions) {
    const Vec2 c = (x - grid_.box().lo) / h;
    const int i = std::clamp(static_cast<int>(std::floor(c.x())), 0, nx - 1);
    const int j = std::clamp(static_cast<int>(std::floor(c.y())), 0, ny - 1);
    active[i + static_cast<std::size_t>(nx) * j] = 1;
  }
  if (active != active_) {  // the Gauss points and their grid weights change with the cells
    active_ = std::move(active);
    points_.clear();
    const double offset = 0.5 / std::sqrt(3.0);  // 2-point Gauss-Legendre on [-1/2, 1/2]
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        if (!active_[i + static_cast<std::size_t>(nx) * j]) continue;
        const Vec2 centre = grid_.box().lo + h * Vec2(i + 0.5, j + 0.5);
        for (const double sy : {-offset, offset})
          for (const double sx : {-offset, offset}) points_.push_back(centre + h * Vec2(sx, sy));
      }
    basis_.resize(weights_, points());
    parallel_blocks(points(), 1024, [&](Index begin, Index end) {
      for (Index g = begin; g < end; ++g) basis_.evaluate(points_[g], Mat2::Identity(), Vec2::Zero(), weights_, g);
    });
    rows_.resize(points_.size());
  }
  const RKShapeFunctions mls(positions, settings_);
  mls.for_each(points_, false, [&](Index g, const ShapeValues& v) {
    rows_[g].particle.assign(v.nodes.begin(), v.nodes.end());  // the rows keep their storage from step to step
    rows_[g].phi.assign(v.phi.begin(), v.phi.end());
  });
}

}  // namespace mfree
