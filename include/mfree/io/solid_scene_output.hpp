#pragma once
// The fields of a solid scene's run, for ParaView ([output] fields; io/solid_scene.hpp):
//
//   volume.vtu   a tetrahedral mesh of the solid (gmsh's tetrahedra; a box split into six
//                tetrahedra per cube of the node spacing) with, at its vertices,
//   surface.vtu  the faces of those tetrahedra on the surface (the same points, so the
//                same values), for a look at the outside. At a tied interface each region
//                has its own copy of the vertices on it, so the stress jumps there as the
//                functions do:
//       displacement  u^h = sum phi_I d_I (never the coefficients)
//       velocity      v^h = sum phi_I v_I (dynamics)
//       stress        Cauchy stress of F^h = I + grad u^h (xx, yy, zz, yz, xz, xy)
//       von_mises     of that stress
//       error         u^h - u against [exact]
//   points.vtu   a law with history (J2, Drucker–Prager) has its stress where its state
//                lives, at the quadrature points: stress, von_mises and plastic_strain (the
//                equivalent plastic strain alpha) there, with u^h; the meshes keep the
//                displacement and the error.
//
// Files are written atomically (io/vtk_output.hpp).

#include <filesystem>
#include <string>
#include <vector>

#include "mfree/galerkin/elasticity_solver.hpp"
#include "mfree/galerkin/total_lagrangian.hpp"
#include "mfree/io/solid_scene.hpp"

namespace mfree {

/// Writes the files above into scene.output.folder, each name followed by `suffix` (a
/// frame's "_0003"); v: the velocity coefficients (dynamics) or null. Returns their paths.
std::vector<std::filesystem::path> write_solid_fields(const SolidScene& scene, const Discretisation<3>& disc,
                                                      const TotalLagrangian<3>& model,
                                                      const Eigen::VectorXd& d,
                                                      const Eigen::VectorXd* v = nullptr,
                                                      const std::string& suffix = "");

}  // namespace mfree
