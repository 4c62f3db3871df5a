#pragma once
// Solids from gmsh files: .geo scripts, .msh meshes and CAD files (STEP, BREP, IGES, read
// through gmsh's OpenCASCADE kernel).
//
// The solid is the union of the file's volumes (its 3D entities), taken as gmsh's mesh of
// tetrahedra Omega_h (geometry/tetrahedral_mesh.hpp): its inside test, its volume, and the
// pieces of the background lattice's cut cells. A file that holds a 3D mesh (a .msh) is used
// as it is; otherwise gmsh meshes it (3D) with the file's own element sizes (point sizes,
// Mesh.MeshSizeMax, size fields; gmsh's configuration files are not read). Higher-order
// tetrahedra contribute their corner nodes: a curved surface enters as the flat triangles of
// its mesh, inscribed in it, so volumes and areas converge at second order in the element size.
//
// The surface is the set of the tetrahedra's faces that belong to one tetrahedron only
// (faces two volumes share are inside), each oriented outward by its tetrahedron. Named parts:
// a face carries the name of the physical surface ("Physical Surface") of the boundary
// surface whose 2D element it is, part -1 where the surface is in none; a group without a
// name is named by its number; Solid::parts() lists the groups on the boundary, by group tag.
// Regions: when the volumes are in physical volumes ("Physical Volume"), each is a region of
// the solid (Solid::regions(), by group tag; a tetrahedron takes its volume's), and a volume in
// none is refused. Volumes that touch need a conforming mesh there (BooleanFragments or
// Coherence in the .geo): a face with the solid on both sides is refused (Solid::from_mesh).
// The faces two regions share are tied interfaces, or with `tied` false inside one set of
// functions (Solid::interfaces()).
//
// gmsh runs in a child process under the limits of the plane reader (gmsh_domain.hpp: one
// session per read, crashes, endless loops and runaway memory end as errors naming the file).

#include <filesystem>

#include "mfree/geometry/gmsh_domain.hpp"
#include "mfree/geometry/solid.hpp"

namespace mfree {

/// Reads the solid of a gmsh file (see above). Throws InputError naming the file when the
/// extension is not one of gmsh_extensions, the file is missing or unreadable, gmsh reports
/// an error (its messages are quoted), the model has no volume, its 3D mesh holds elements
/// other than tetrahedra (naming the element type and the volume), a .msh holds no
/// tetrahedra, a boundary surface is in two physical surfaces, the tetrahedra fail
/// TetrahedralMesh's checks or the surface Solid::from_mesh's, gmsh crashes on the file or
/// exceeds a limit. Throws Error when the reader process is killed from outside or fails.
[[nodiscard]] Solid read_gmsh_solid(const std::filesystem::path& file,
                                    const GmshReaderLimits& limits = default_gmsh_reader_limits(),
                                    bool tied = true);

}  // namespace mfree
