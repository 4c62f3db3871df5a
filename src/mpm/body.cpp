#include "mfree/mpm/body.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "mfree/core/error.hpp"
#include "mfree/core/memory.hpp"

namespace mfree {

const NameTable<Shape>& shape_names() {
  static const NameTable<Shape> table{{"rectangle", Shape::rectangle}, {"circle", Shape::circle}, {"polygon", Shape::polygon}};
  return table;
}

MPMBody rectangle_body(std::string name, const Box& box) {
  MPMBody b;
  b.name = std::move(name);
  b.shape = Shape::rectangle;
  b.bounds = box;
  b.contains = [box](const Vec2& x) { return box.contains(x); };
  b.where = fmt::format("body '{}'", b.name);
  return b;
}

namespace {

/// The cells [first, last] of an axis from lo with spacing h and `cells` cells that the
/// interval [a, b] meets.
std::pair<int, int> cell_range(double lo, double h, int cells, double a, double b) {
  const int first = std::clamp(static_cast<int>(std::floor((a - lo) / h)), 0, cells - 1);
  const int last = std::clamp(static_cast<int>(std::ceil((b - lo) / h)) - 1, 0, cells - 1);
  return {first, last};
}

/// A lower bound of what a particle holds: its own arrays (positions, velocity, F, stress,
/// mass, volume, domain) and the grid functions at it (9 to 16 nodes, value and gradient).
constexpr double bytes_per_particle = 512.0;

/// The particles per side of a body, checked.
int per_side_of(const MPMBody& body, int default_per_side) {
  const int n = body.particles_per_side > 0 ? body.particles_per_side : default_per_side;
  if (n < 1 || n > 5)
    throw InputError(
        fmt::format("{}: 1 to 5 particles per cell side (1 to 25 per cell), got {}", body.where, n));
  return n;
}

/// Refuses a body whose bounds reach outside the grid box (to tol).
void check_inside(const MPMBody& body, const Box& box, double tol) {
  const Box& bb = body.bounds;
  if ((bb.lo.array() < box.lo.array() - tol).any() || (bb.hi.array() > box.hi.array() + tol).any())
    throw InputError(fmt::format(
        "{}: body '{}' reaches outside the grid box: it spans [{:.6g}, {:.6g}] x [{:.6g}, {:.6g}], the box "
        "[{:.6g}, {:.6g}] x [{:.6g}, {:.6g}]; enlarge the grid box or move the body",
        body.where, body.name, bb.lo.x(), bb.hi.x(), bb.lo.y(), bb.hi.y(), box.lo.x(), box.hi.x(), box.lo.y(),
        box.hi.y()));
}

/// The sub-cells [i0, i1) x [j0, j1) (in units of h / n from the box's corner) of the cells
/// that a body's bounding box meets: the candidates for its particles.
struct SubCells {
  int i0 = 0, i1 = 0, j0 = 0, j1 = 0;
  [[nodiscard]] double count() const { return static_cast<double>(i1 - i0) * (j1 - j0); }
};
SubCells sub_cells(const MPMBody& body, const Box& box, double h, int n) {
  const int cells_x = static_cast<int>(std::lround(box.size().x() / h));
  const int cells_y = static_cast<int>(std::lround(box.size().y() / h));
  const auto [i0, i1] = cell_range(box.lo.x(), h, cells_x, body.bounds.lo.x(), body.bounds.hi.x());
  const auto [j0, j1] = cell_range(box.lo.y(), h, cells_y, body.bounds.lo.y(), body.bounds.hi.y());
  return {i0 * n, (i1 + 1) * n, j0 * n, (j1 + 1) * n};
}

}  // namespace

Particles seed_bodies(const std::vector<MPMBody>& bodies, const std::vector<MPMMaterial>& materials,
                      const Box& box, double h, int default_per_side, bool with_domains,
                      const VelocityCheck& check_velocity) {
  const double tol = 1e-12 * box.size().norm();
  // Every body's checks and the count of all the particles (at most) before any is seeded.
  double total = 0.0;
  for (const MPMBody& body : bodies) {
    const int n = per_side_of(body, default_per_side);
    check_inside(body, box, tol);
    const double seeded = sub_cells(body, box, h, n).count();
    total += seeded;
    if (total > std::numeric_limits<Index>::max())
      throw InputError(
          fmt::format("{}: body '{}' would take up to {:.3g} particles ({:.3g} with the bodies before "
                      "it), more than the {} a problem may have; use fewer cells or particles per cell",
                      body.where, body.name, seeded, total, std::numeric_limits<Index>::max()));
  }
  if (!bodies.empty())
    check_memory(total * bytes_per_particle,
                 bodies.size() == 1
                     ? fmt::format("{}: the particles of body '{}' (up to {:.3g})", bodies.front().where,
                                   bodies.front().name, total)
                     : fmt::format("the particles of the {} bodies (up to {:.3g}; the first, '{}', at {})",
                                   bodies.size(), total, bodies.front().name, bodies.front().where));
  Particles P;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const MPMBody& body = bodies[b];
    const int n = per_side_of(body, default_per_side);
    const double d = h / n;  // particle spacing
    const double density = materials.at(static_cast<std::size_t>(body.material)).density;
    const SubCells c = sub_cells(body, box, h, n);
    const Index before = P.size();
    // Row by row of sub-cells (y outer, x inner), as fill_box() orders a full box.
    for (int j = c.j0; j < c.j1; ++j)
      for (int i = c.i0; i < c.i1; ++i) {
        const Vec2 X = box.lo + Vec2((i + 0.5) * d, (j + 0.5) * d);
        if (!body.contains(X)) continue;
        for (std::size_t a = 0; a < b; ++a)
          if (bodies[a].contains(X))
            throw InputError(fmt::format("{}: body '{}' overlaps body '{}' ({}) at ({:.6g}, {:.6g}); bodies may not "
                                         "overlap: move one or shrink it",
                                         body.where, body.name, bodies[a].name, bodies[a].where, X.x(), X.y()));
        const Vec2 v = body.initial_velocity ? body.initial_velocity(X) : Vec2::Zero();
        if (!v.allFinite())
          throw InputError(
              fmt::format("{}: body '{}': the initial velocity at X = ({:.6g}, {:.6g}) is not a "
                          "finite number; give a finite velocity",
                          body.velocity_key(), body.name, X.x(), X.y()));
        if (check_velocity) check_velocity(body, X, v);
        P.mass.push_back(density * d * d);
        P.volume0.push_back(d * d);
        P.volume.push_back(d * d);
        P.reference.push_back(X);
        P.velocity.push_back(v);
        if (with_domains) P.half_size.emplace_back(0.5 * d, 0.5 * d);
        P.body.push_back(static_cast<int>(b));
        P.material.push_back(body.material);
      }
    if (P.size() == before)
      throw InputError(fmt::format("{}: body '{}' gets no particles: no sub-cell centre (spacing {:.4g}) lies in its "
                                   "shape; make it larger, the grid finer or particles_per_cell larger",
                                   body.where, body.name, d));
  }
  P.position = P.reference;
  P.deformation.assign(P.mass.size(), Mat2::Identity());
  P.stress.assign(P.mass.size(), Mat2::Zero());
  P.stress_zz.assign(P.mass.size(), 0.0);
  P.state.assign(P.mass.size(), MaterialState<2>{});
  return P;
}

}  // namespace mfree
