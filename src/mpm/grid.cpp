#include "mfree/mpm/grid.hpp"

#include <cmath>
#include <fmt/format.h>

#include "mfree/core/error.hpp"

namespace mfree {

namespace {

int rows_for(const Box& d, int cells_x) {
  if (cells_x < 1) throw InputError(fmt::format("MPM grid: needs at least one cell per side (got {})", cells_x));
  const double h = d.size().x() / cells_x;
  const double rows = d.size().y() / h;
  if (!(h > 0.0) || std::abs(rows - std::round(rows)) > 1e-9 * rows || std::round(rows) < 1)
    throw InputError(fmt::format("MPM grid: the domain {} x {} is not a whole number of square cells of size {}",
                                 d.size().x(), d.size().y(), h));
  return static_cast<int>(std::round(rows));
}

}  // namespace

Grid::Grid(const Box& domain, int cells_x, int degree, int pad)
    : domain_(domain),
      cells_x_(cells_x),
      cells_y_(rows_for(domain, cells_x)),
      ax_(domain.lo.x() - pad * domain.size().x() / cells_x, domain.size().x() / cells_x, cells_x + 2 * pad, degree),
      ay_(domain.lo.y() - pad * domain.size().x() / cells_x, domain.size().x() / cells_x, cells_y_ + 2 * pad, degree) {}

std::vector<unsigned char> Grid::wall_mask(const std::vector<Wall>& walls) const {
  std::vector<unsigned char> mask(static_cast<std::size_t>(size()), 0);
  const double tol = 1e-9 * spacing();
  for (Index n = 0; n < size(); ++n) {
    const Vec2 x = node(n);
    for (Wall w : walls) {
      if ((w == Wall::left && x.x() <= domain_.lo.x() + tol) || (w == Wall::right && x.x() >= domain_.hi.x() - tol))
        mask[n] |= 1;
      if ((w == Wall::bottom && x.y() <= domain_.lo.y() + tol) || (w == Wall::top && x.y() >= domain_.hi.y() - tol))
        mask[n] |= 2;
    }
  }
  return mask;
}

}  // namespace mfree
