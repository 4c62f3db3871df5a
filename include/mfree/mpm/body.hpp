#pragma once
// The bodies of an MPM problem and the materials they are made of: each body is a shape in
// the grid box, filled with particles of one material at t = 0.
//
// Seeding: in every cell of the grid (size h) that the shape's bounding box meets, the
// centres of the regular n x n subdivision of the cell (n = particles per side) that lie in
// the shape (boundary included) become particles, each of volume (h / n)^2, mass
// rho0 (h / n)^2, F = I, zero stress, and the body's initial velocity at its position. A
// body that fills whole cells gets exactly the particles of fill_box(); a curved or slanted
// edge is resolved to the sub-cell size h / n (the seeded area differs from the shape's by
// about perimeter x h / (2n) at most).
//
// Nothing is silently dropped or shared: a body without particles, a body reaching outside
// the grid box, a sub-cell centre inside two bodies (overlapping bodies) and an initial
// velocity that is not finite are input errors naming the body's scene key.
//
// Cheap checks first: every body's place in the box, its particles per cell, and the count
// and memory of all the particles (an upper bound, the sub-cells of the cells their bounding
// boxes meet) are checked before the first particle is seeded.

#include <functional>
#include <string>
#include <vector>

#include "mfree/core/name_table.hpp"
#include "mfree/core/types.hpp"
#include "mfree/materials/material.hpp"
#include "mfree/mpm/particles.hpp"

namespace mfree {

/// A material of the problem, by the name bodies refer to it with.
struct MPMMaterial {
  std::string name;
  Material law;
  double density = 0.0;  ///< rho0 [kg/m^3]
};

/// The shapes a body can have.
enum class Shape { rectangle, circle, polygon };
/// rectangle, circle, polygon.
const NameTable<Shape>& shape_names();

struct MPMBody {
  std::string name;
  Shape shape = Shape::rectangle;
  std::function<bool(const Vec2&)> contains;  ///< the shape's inside test, boundary included
  Box bounds;                                 ///< a box holding the shape
  int material = 0;                           ///< index into the problem's materials
  int particles_per_side = 0;                 ///< per cell side; 0: the settings' default
  std::function<Vec2(const Vec2& X)> initial_velocity;  ///< [m/s]; empty: at rest
  /// Where the body is defined, for messages ("scene.toml:20:1: key 'body[1].shape'").
  std::string where;
  /// Where its initial velocity is given ("scene.toml:22:1: key 'body[1].velocity'"); empty:
  /// `where`.
  std::string velocity_where;
  /// velocity_where, or where when that is empty.
  [[nodiscard]] const std::string& velocity_key() const {
    return velocity_where.empty() ? where : velocity_where;
  }
};

/// Called for every particle as it is seeded, with its body, reference position X and
/// initial velocity v (finite): throws to refuse it (the solver's check of v against the
/// time step and the grid).
using VelocityCheck = std::function<void(const MPMBody& body, const Vec2& X, const Vec2& v)>;

/// The body that is the rectangle `box`: material 0, the settings' particles per cell, at rest.
MPMBody rectangle_body(std::string name, const Box& box);

/// The particles of every body (body b's particles carry body index b and its material),
/// seeded in the cells of size h of `box` as above; default_per_side where a body states
/// none; with_domains fills half_size = (h / (2n), h / (2n)) (uses_domains() methods). Throws InputError
/// (naming the body's `where`) for a body outside the box, one without particles, overlapping
/// bodies, a per-side count outside [1, 5], more particles than an Index holds or than the
/// memory takes (before any is seeded), and (naming velocity_key()) a non-finite initial
/// velocity; check_velocity (if given) sees every particle's initial velocity.
Particles seed_bodies(const std::vector<MPMBody>& bodies, const std::vector<MPMMaterial>& materials,
                      const Box& box, double h, int default_per_side, bool with_domains,
                      const VelocityCheck& check_velocity = {});

}  // namespace mfree
