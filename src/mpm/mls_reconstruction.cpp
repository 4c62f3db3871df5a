#include "mfree/mpm/mls_reconstruction.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "mfree/kernels/rk_moment.hpp"
#include "mfree/kernels/window_function.hpp"

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
  const std::size_t cells = static_cast<std::size_t>(nx) * ny;

  // The particles binned by half cells (a counting sort; a particle outside the box in the
  // bin next to it), their positions copied in bin order, and the cells holding particles
  // marked. Half cells: a cell's Gauss points reach 1.79 h (support 1.5 h) to each side, 4 h
  // of half-cell bins against 5 h of whole cells, two thirds of the candidates to test.
  const int bx = 2 * nx, by = 2 * ny;
  const std::size_t bins = static_cast<std::size_t>(bx) * by;
  std::vector<unsigned char> active(cells, 0);
  bin_cell_.resize(positions.size());
  bin_start_.assign(bins + 1, 0);
  for (std::size_t p = 0; p < positions.size(); ++p) {
    const Vec2 c = (positions[p] - grid_.box().lo) * (2.0 / h);
    const int i = std::clamp(static_cast<int>(std::floor(c.x())), 0, bx - 1);
    const int j = std::clamp(static_cast<int>(std::floor(c.y())), 0, by - 1);
    bin_cell_[p] = i + bx * j;
    ++bin_start_[bin_cell_[p] + 1];
    active[i / 2 + static_cast<std::size_t>(nx) * (j / 2)] = 1;
  }
  for (std::size_t b = 0; b < bins; ++b) bin_start_[b + 1] += bin_start_[b];
  bin_particle_.resize(positions.size());
  bin_position_.resize(positions.size());
  {
    std::vector<Index> next(bin_start_.begin(), bin_start_.end() - 1);
    for (std::size_t p = 0; p < positions.size(); ++p) {
      const Index k = next[bin_cell_[p]]++;
      bin_particle_[k] = static_cast<Index>(p);
      bin_position_[k] = positions[p];
    }
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
    rows_.resize(points_.size() / 4);
  }
  if (settings_.order == RKOrder::linear) update_rows<1>(positions);
  else update_rows<2>(positions);
}

/// The MLS functions of the four Gauss points of every active cell in one pass over the
/// particles of the cells their supports reach: the tensor window is a product, so the two
/// x and two y offsets of a particle give its four windows from four 1D evaluations, and
/// the four moment matrices fill side by side, one per lane of an Eigen::Array4d
/// (rk_moment.hpp). The same functions as RKShapeFunctions with the particles as nodes
/// (quadratic spline window, tensor support of half width a), summed in another order.
template <int Order>
void MLSReconstruction::update_rows(const std::vector<Vec2>& positions) {
  using Basis = PolynomialBasis<Order>;
  using Lanes = Eigen::Array4d;  // lane q: Gauss point q of the cell
  using Moment = RKMoment<Order, Lanes>;
  const double h = grid_.spacing(), a = settings_.radius, inv_a = 1.0 / a;
  const Vec2 lo = grid_.box().lo;
  const int nx = grid_.cells_x(), ny = grid_.cells_y();
  const int bx = 2 * nx, by = 2 * ny;  // half-cell bins
  const auto column = [&](double x) { return std::clamp(static_cast<int>(std::floor((x - lo.x()) * 2.0 / h)), 0, bx - 1); };
  const auto row_of = [&](double y) { return std::clamp(static_cast<int>(std::floor((y - lo.y()) * 2.0 / h)), 0, by - 1); };
  // The scaled offsets z = (x_g - x_p) / a of the four points, lane q = (q & 1, q >> 1).
  const auto offsets = [&](const Vec2& x, const Vec2& g0, const Vec2& g1, Lanes& z1, Lanes& z2) {
    const double x0 = (g0.x() - x.x()) * inv_a, x1 = (g1.x() - x.x()) * inv_a;
    const double y0 = (g0.y() - x.y()) * inv_a, y1 = (g1.y() - x.y()) * inv_a;
    z1 << x0, x1, x0, x1;
    z2 << y0, y0, y1, y1;
  };

  parallel_blocks(static_cast<Index>(rows_.size()), 16, [&](Index begin, Index end) {
    for (Index c = begin; c < end; ++c) {
      const Vec2 g0 = points_[4 * c], g1 = points_[4 * c + 3];  // the (-,-) and (+,+) points
      Row& row = rows_[c];
      row.particle.clear();  // the rows keep their storage from step to step
      row.phi.clear();
      Moment moment;
      // Pass 1: windows (phi holds w until pass 2) and moments, for the particles inside
      // the union of the four supports.
      const double xlo = g0.x() - a, xhi = g1.x() + a, ylo = g0.y() - a, yhi = g1.y() + a;
      const int i0 = column(xlo), i1 = column(xhi);
      for (int j = row_of(ylo); j <= row_of(yhi); ++j)
        for (Index k = bin_start_[i0 + bx * j]; k < bin_start_[i1 + bx * j + 1]; ++k) {
          const Vec2& x = bin_position_[k];
          if (!(x.x() > xlo && x.x() < xhi && x.y() > ylo && x.y() < yhi)) continue;
          Lanes z1, z2;
          offsets(x, g0, g1, z1, z2);
          const double wx0 = quadratic_spline(std::abs(z1[0])).w, wx1 = quadratic_spline(std::abs(z1[1])).w;
          const double wy0 = quadratic_spline(std::abs(z2[0])).w, wy1 = quadratic_spline(std::abs(z2[2])).w;
          const Lanes w = Lanes(wx0, wx1, wx0, wx1) * Lanes(wy0, wy0, wy1, wy1);
          moment.add(w, Basis::value(z1, z2));
          row.particle.push_back(bin_particle_[k]);
          row.phi.push_back(w);
        }
      // b = M^-1 H(0) of each point, lane by lane: b[i][q].
      std::array<Lanes, Moment::nb> b;
      for (int q = 0; q < 4; ++q) {
        typename RKMoment<Order>::Matrix inverse;
        const double rcond = moment.lane(q).invert(inverse);
        if (!(rcond >= settings_.rcond_min)) {  // fewer than nb particles, or too regular: name the point
          const auto n = static_cast<std::size_t>(
              std::count_if(row.phi.begin(), row.phi.end(), [q](const Lanes& w) { return w[q] > 0.0; }));
          throw_moment_failure(points_[4 * c + q], n, settings_, n < static_cast<std::size_t>(Moment::nb) ? -1.0 : rcond,
                               "Increase [mpm] mls_support, use mls_basis = \"linear\" or more particles per cell "
                               "near this point.");
        }
        for (int i = 0; i < Moment::nb; ++i) b[i][q] = inverse(i, 0);
      }
      // Pass 2: phi_gp = b . H(z) w.
      for (std::size_t k = 0; k < row.particle.size(); ++k) {
        Lanes z1, z2;
        offsets(positions[row.particle[k]], g0, g1, z1, z2);
        const auto terms = Basis::value(z1, z2);
        Lanes bh = b[0] * terms[0];
        for (int i = 1; i < Moment::nb; ++i) bh += b[i] * terms[i];
        row.phi[k] *= bh;
      }
    }
  });
}

}  // namespace mfree
