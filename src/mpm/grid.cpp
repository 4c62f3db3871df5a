#include "mfree/mpm/grid.hpp"

#include <cmath>
#include <fmt/format.h>

#include "mfree/core/error.hpp"
#include "mfree/core/memory.hpp"

namespace mfree {

namespace {

int rows_for(const Box& d, int cells_x) {
  if (cells_x < 1) throw InputError(fmt::format("MPM grid: needs at least one cell per side (got {})", cells_x));
  const double h = d.size().x() / cells_x;
  const double rows = d.size().y() / h;
  if (!(h > 0.0) || std::abs(rows - std::round(rows)) > 1e-9 * rows || std::round(rows) < 1)
    throw InputError(fmt::format("MPM grid: the box {} x {} is not a whole number of square cells of size {}",
                                 d.size().x(), d.size().y(), h));
  // Node arrays (mass, momentum, velocity, force, wall mask): about 96 bytes a node.
  check_memory((cells_x + 5.0) * (std::round(rows) + 5.0) * 96.0,
               fmt::format("MPM: the grid of {} x {} cells ([mpm] cells)", cells_x, std::round(rows)));
  return static_cast<int>(std::round(rows));
}

}  // namespace

const NameTable<Side>& side_names() {
  static const NameTable<Side> table{{"left", Side::left}, {"right", Side::right}, {"bottom", Side::bottom}, {"top", Side::top}};
  return table;
}

const NameTable<Wall>& wall_names() {
  static const NameTable<Wall> table{{"open", Wall::open}, {"slip", Wall::slip}, {"fixed", Wall::fixed}};
  return table;
}

Grid::Grid(const Box& box, int cells_x, int degree, int pad)
    : box_(box),
      cells_x_(cells_x),
      cells_y_(rows_for(box, cells_x)),
      ax_(box.lo.x() - pad * box.size().x() / cells_x, box.size().x() / cells_x, cells_x + 2 * pad, degree),
      ay_(box.lo.y() - pad * box.size().x() / cells_x, box.size().x() / cells_x, cells_y_ + 2 * pad, degree) {}

std::vector<unsigned char> Grid::wall_mask(const Walls& walls) const {
  std::vector<unsigned char> mask(static_cast<std::size_t>(size()), 0);
  const double tol = 1e-9 * spacing();
  // The bits a side's wall holds: its normal component (slip) or both (fixed).
  const auto held = [&](Side side, unsigned char normal) -> unsigned char {
    const Wall w = walls[static_cast<std::size_t>(side)];
    return w == Wall::fixed ? 3 : w == Wall::slip ? normal : 0;
  };
  for (Index n = 0; n < size(); ++n) {
    const Vec2 x = node(n);
    if (x.x() <= box_.lo.x() + tol) mask[n] |= held(Side::left, 1);
    if (x.x() >= box_.hi.x() - tol) mask[n] |= held(Side::right, 1);
    if (x.y() <= box_.lo.y() + tol) mask[n] |= held(Side::bottom, 2);
    if (x.y() >= box_.hi.y() - tol) mask[n] |= held(Side::top, 2);
  }
  return mask;
}

}  // namespace mfree
