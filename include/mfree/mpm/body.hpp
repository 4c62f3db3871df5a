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
// the grid box, and a sub-cell centre inside two bodies (overlapping bodies) are input
// errors naming the body's scene key.

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
};

/// The body that is the rectangle `box`: material 0, the settings' particles per cell, at rest.
MPMBody rectangle_body(std::string name, const Box& box);

/// The particles of every body (body b's particles carry body index b and its material),
/// seeded in the cells of size h of `box` as above; default_per_side where a body states
/// none; with_domains fills half_size = (h / (2n), h / (2n)) (uses_domains() methods). Throws InputError
/// (naming the body's `where`) for a body outside the box, one without particles, overlapping
/// bodies, or a per-side count outside [1, 5].
Particles seed_bodies(const std::vector<MPMBody>& bodies, const std::vector<MPMMaterial>& materials, const Box& box,
                      double h, int default_per_side, bool with_domains);

}  // namespace mfree
