#pragma once
// VTK output of an elasticity solve, for ParaView. Only the fields the scene asks for
// ([output] fields) are computed and written:
//
//   nodes.vtu       the DOF cloud: u^h(x_I) = sum_J phi_J(x_I) d_J (never the coefficients),
//                   stress and von Mises from the gradients of u^h, exact values and errors
//   quadrature.vtu  the quadrature cloud: weights, and the stress the weak form used there
//                   (the consistent gradients of the quadrature)
//   field.vtu       u^h and stresses on a constrained Delaunay triangulation of the nodes that
//                   respects holes and notches: the file for contour plots
//
// Stress is given as the Voigt triple (xx, yy, xy). Files are written atomically.

#include <filesystem>
#include <vector>

#include "mfree/galerkin/elasticity_solver.hpp"
#include "mfree/io/elasticity_scene.hpp"

namespace mfree {

/// Writes the files above into scene.output.folder; returns their paths.
std::vector<std::filesystem::path> write_elasticity_fields(const ElasticityScene& scene, const ElasticityResult& r);

}  // namespace mfree
