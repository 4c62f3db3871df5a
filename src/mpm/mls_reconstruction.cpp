#include "mfree/mpm/mls_reconstruction.hpp"

#include <algorithm>
#include <atomic>
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

void MLSReconstruction::update(const std::vector<Vec2>& positions, const std::vector<Mat2>& deformation,
                               const std::vector<double>& volume0) {
  const double h = grid_.spacing();
  const int nx = grid_.cells_x(), ny = grid_.cells_y();

  // The particles binned by half cells (a counting sort; a particle outside the box in the
  // bin next to it), their positions copied in bin order. Half cells: a cell's Gauss points
  // reach 1.79 h (support 1.5 h) to each side, 4 h of half-cell bins against 5 h of whole
  // cells, two thirds of the candidates to test.
  const int bx = 2 * nx, by = 2 * ny;
  const std::size_t bins = static_cast<std::size_t>(bx) * by;
  bin_cell_.resize(positions.size());
  bin_start_.assign(bins + 1, 0);
  for (std::size_t p = 0; p < positions.size(); ++p) {
    const Vec2 c = (positions[p] - grid_.box().lo) * (2.0 / h);
    const int i = std::clamp(static_cast<int>(std::floor(c.x())), 0, bx - 1);
    const int j = std::clamp(static_cast<int>(std::floor(c.y())), 0, by - 1);
    bin_cell_[p] = i + bx * j;
    ++bin_start_[bin_cell_[p] + 1];
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

  // The data of the reconstruction: the particles of the interior cells.
  std::vector<unsigned char> interior;
  interior_cells(positions, deformation, volume0, interior);
  const auto cell_of_bin = [&](Index b) {
    return (b % bx) / 2 + static_cast<std::size_t>(nx) * ((b / bx) / 2);
  };
  is_data_.resize(positions.size());
  for (std::size_t p = 0; p < positions.size(); ++p) is_data_[p] = interior[cell_of_bin(bin_cell_[p])];
  // Gauss points in the interior cells; a cell where one of them sees too few data for the
  // moment matrix returns to its particles' quadrature (the rows of the others stand: they
  // read the same data).
  place_gauss_points(interior);
  const std::vector<unsigned char> failed =
      settings_.order == RKOrder::linear ? update_rows<1>(positions) : update_rows<2>(positions);
  demoted_ = std::count(failed.begin(), failed.end(), 1);
  if (demoted_ > 0) {
    std::size_t kept = 0;
    for (std::size_t c = 0; c < rows_.size(); ++c)
      if (!failed[c]) std::swap(rows_[kept++], rows_[c]);
    rows_.resize(kept);  // before the cells go: place_gauss_points resizes the rows to the cells
    std::size_t c = 0;
    for (unsigned char& cell : interior)
      if (cell && failed[c++]) cell = 0;
    place_gauss_points(interior);
  }
  // The particles of the other cells (a particle's cell: its half-cell bin's), their own
  // quadrature points, after the Gauss points.
  own_.clear();
  for (std::size_t p = 0; p < positions.size(); ++p)
    if (!gauss_cells_[cell_of_bin(bin_cell_[p])]) own_.push_back(static_cast<Index>(p));
  basis_.resize(weights_, points());
  parallel_blocks(static_cast<Index>(own_.size()), 1024, [&](Index begin, Index end) {
    for (Index k = begin; k < end; ++k)
      basis_.evaluate(positions[own_[k]], Mat2::Identity(), Vec2::Zero(), weights_, gauss_count() + k);
  });
}

void MLSReconstruction::place_gauss_points(const std::vector<unsigned char>& cells) {
  if (cells == gauss_cells_) return;  // the Gauss points and their grid weights change with the cells
  gauss_cells_ = cells;
  const double h = grid_.spacing();
  const int nx = grid_.cells_x(), ny = grid_.cells_y();
  points_.clear();
  const double offset = 0.5 / std::sqrt(3.0);  // 2-point Gauss-Legendre on [-1/2, 1/2]
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      if (!gauss_cells_[i + static_cast<std::size_t>(nx) * j]) continue;
      const Vec2 centre = grid_.box().lo + h * Vec2(i + 0.5, j + 0.5);
      for (const double sy : {-offset, offset})
        for (const double sx : {-offset, offset}) points_.push_back(centre + h * Vec2(sx, sy));
    }
  basis_.resize(weights_, gauss_count());
  parallel_blocks(gauss_count(), 1024, [&](Index begin, Index end) {
    for (Index g = begin; g < end; ++g)
      basis_.evaluate(points_[g], Mat2::Identity(), Vec2::Zero(), weights_, g);
  });
  rows_.resize(points_.size() / 4);
}

/// interior[c] = 1 where the bodies fill cell c and its neighbours on the grid. Filled: the
/// particle domains cover the cell's corners, edge midpoints and centre (a lattice of half
/// cells, 9 points a cell, shared). Domain of p: x_p + F_p xi with |xi_x|, |xi_y| <= (1 +
/// 1/4) sqrt(V_p0) / 2; a lattice point s is in it when |F_p^-1 (s - x_p)|_inf <= that half
/// width.
void MLSReconstruction::interior_cells(const std::vector<Vec2>& positions,
                                       const std::vector<Mat2>& deformation,
                                       const std::vector<double>& volume0,
                                       std::vector<unsigned char>& interior) const {
  const double h = grid_.spacing(), half_step = 0.5 * h;
  const Vec2 lo = grid_.box().lo;
  const int nx = grid_.cells_x(), ny = grid_.cells_y(), sx = 2 * nx + 1, sy = 2 * ny + 1;
  std::vector<unsigned char> covered(static_cast<std::size_t>(sx) * sy, 0);
  parallel_blocks(static_cast<Index>(positions.size()), 1024, [&](Index begin, Index end) {
    for (Index p = begin; p < end; ++p) {
      const double r = 1.25 * 0.5 * std::sqrt(volume0[p]);
      const Mat2& F = deformation[p];
      const Mat2 inverse = F.inverse();
      const Vec2 extent = r * F.cwiseAbs().rowwise().sum();  // half sizes of the domain's bounding box
      // The lattice range, clamped before the conversion to int (a domain may reach far).
      const Vec2 limit(sx, sy);
      const Vec2 a = ((positions[p] - extent - lo) / half_step).cwiseMax(Vec2::Zero()).cwiseMin(limit);
      const Vec2 b = ((positions[p] + extent - lo) / half_step).cwiseMax(Vec2::Constant(-1.0)).cwiseMin(limit);
      const int i0 = std::max(0, static_cast<int>(std::ceil(a.x())));
      const int i1 = std::min(sx - 1, static_cast<int>(std::floor(b.x())));
      const int j0 = std::max(0, static_cast<int>(std::ceil(a.y())));
      const int j1 = std::min(sy - 1, static_cast<int>(std::floor(b.y())));
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) {
          const Vec2 xi = inverse * (lo + half_step * Vec2(i, j) - positions[p]);
          // Threads may mark a point at once: the same value, an atomic store.
          if (xi.cwiseAbs().maxCoeff() <= r)
            std::atomic_ref<unsigned char>(covered[i + static_cast<std::size_t>(sx) * j])
                .store(1, std::memory_order_relaxed);
        }
    }
  });
  std::vector<unsigned char> filled(static_cast<std::size_t>(nx) * ny, 0);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      bool all = true;
      for (int dj = 0; dj <= 2 && all; ++dj)
        for (int di = 0; di <= 2 && all; ++di)
          all = covered[2 * i + di + static_cast<std::size_t>(sx) * (2 * j + dj)];
      filled[i + static_cast<std::size_t>(nx) * j] = all;
    }
  interior = filled;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      for (int b = std::max(j - 1, 0); b <= std::min(j + 1, ny - 1); ++b)
        for (int a = std::max(i - 1, 0); a <= std::min(i + 1, nx - 1); ++a)
          if (!filled[a + static_cast<std::size_t>(nx) * b])
            interior[i + static_cast<std::size_t>(nx) * j] = 0;
}

/// The MLS functions of the four Gauss points of every interior cell in one pass over the
/// particles of the cells their supports reach: the tensor window is a product, so the two
/// x and two y offsets of a particle give its four windows from four 1D evaluations, and
/// the four moment matrices fill side by side, one per lane of an Eigen::Array4d
/// (rk_moment.hpp). The same functions as RKShapeFunctions<2> with the particles as nodes
/// (quadratic spline window, tensor support of half width a), summed in another order.
template <int Order>
std::vector<unsigned char> MLSReconstruction::update_rows(const std::vector<Vec2>& positions) {
  using Basis = PolynomialBasis<2, Order>;
  using Lanes = Eigen::Array4d;  // lane q: Gauss point q of the cell
  using Moment = RKMoment<2, Order, Lanes>;
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

  std::vector<unsigned char> failed(rows_.size(), 0);
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
          if (!is_data_[bin_particle_[k]]) continue;
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
        typename RKMoment<2, Order>::Matrix inverse;
        // Fewer than nb particles, or too regular (on a line; on a conic for the quadratic basis).
        if (!(moment.lane(q).invert(inverse) >= settings_.rcond_min)) failed[c] = 1;
        for (int i = 0; i < Moment::nb; ++i) b[i][q] = inverse(i, 0);
      }
      if (failed[c]) continue;
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
  return failed;
}

}  // namespace mfree
