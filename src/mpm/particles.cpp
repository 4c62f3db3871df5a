#include "mfree/mpm/particles.hpp"

#include <cmath>
#include <fmt/format.h>

#include "mfree/core/error.hpp"

namespace mfree {

std::string particle_name(const Particles& P, Index p) {
  return fmt::format("particle {} (started at ({:.6g}, {:.6g}))", p, P.reference[p].x(), P.reference[p].y());
}

Particles fill_box(const Box& box, double h, int per_side, double density, bool with_domains) {
  if (per_side < 1 || per_side > 5)
    throw InputError(fmt::format("particles: 1 to 5 particles per cell side (1 to 25 per cell), got {}", per_side));
  const Vec2 cells = box.size() / h;
  const int nx = static_cast<int>(std::round(cells.x())), ny = static_cast<int>(std::round(cells.y()));
  if (nx < 1 || ny < 1 || std::abs(cells.x() - nx) > 1e-9 * nx || std::abs(cells.y() - ny) > 1e-9 * ny)
    throw InputError(fmt::format("particles: the box {} x {} is not a whole number of cells of size {}", box.size().x(),
                                 box.size().y(), h));
  const int mx = nx * per_side, my = ny * per_side;
  const double d = h / per_side;  // particle spacing
  Particles p;
  const std::size_t n = static_cast<std::size_t>(mx) * my;
  p.mass.assign(n, density * d * d);
  p.volume0.assign(n, d * d);
  p.volume.assign(n, d * d);
  p.reference.resize(n);
  for (int j = 0; j < my; ++j)
    for (int i = 0; i < mx; ++i) p.reference[i + static_cast<std::size_t>(mx) * j] = box.lo + Vec2((i + 0.5) * d, (j + 0.5) * d);
  p.position = p.reference;
  p.velocity.assign(n, Vec2::Zero());
  p.deformation.assign(n, Mat2::Identity());
  p.stress.assign(n, Mat2::Zero());
  p.stress_zz.assign(n, 0.0);
  p.state.assign(n, MaterialState<2>{});
  if (with_domains) p.half_size.assign(n, Vec2(0.5 * d, 0.5 * d));
  p.body.assign(n, 0);
  p.material.assign(n, 0);
  return p;
}

}  // namespace mfree
