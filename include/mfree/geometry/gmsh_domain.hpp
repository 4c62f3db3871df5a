#pragma once
// Domains from gmsh files: .geo scripts, .msh meshes and CAD files (STEP, BREP, IGES, read
// through gmsh's OpenCASCADE kernel).
//
// The domain is the union of the file's surfaces (its 2D entities), which must lie in the
// plane z = 0 and form one connected region, with or without holes. Its boundary is the set of
// curves that bound exactly one surface (curves shared by two surfaces are interior, or
// interfaces between regions: see below), taken as
// polygons from gmsh's 1D mesh: the end nodes of the line elements on those curves, chained
// into closed rings whatever the curves' orientations. The polygon is inscribed in a curved
// boundary (its vertices lie on the curves, its edges are chords), so areas and lengths
// converge to the curved values at second order in the element size.
//
// Element sizes are the file's own (point sizes, Mesh.MeshSizeMax = Mesh.CharacteristicLengthMax,
// size fields, transfinite curves); gmsh's configuration files are not read, so they are the
// same on every machine. A file that holds a 1D mesh (a .msh) is used as it is; otherwise gmsh
// meshes the curves (1D only). Higher-order line elements contribute their end nodes only. CAD
// files carry no sizes: gmsh's defaults apply (coarse: two pieces per quarter circle); a .geo
// that merges the CAD file (Merge "part.step";) can set sizes and physical curves.
//
// Named boundary parts: every boundary edge carries the name of the dim-1 physical group
// ("Physical Curve") of its curve, -1 for curves in none; a group without a name is named by
// its number ("7"). Domain::part_names() lists the groups on the boundary, by group tag.
//
// Regions (Domain::from_regions): when the model has dim-2 physical groups ("Physical
// Surface"), each is a region of the domain, named by its group (by its number for a group
// without a name; groups of one name are one region), in the order of the group tags. Every
// surface then belongs to exactly one of them. A region is one connected polygon with holes:
// the curves bounding exactly one of its surfaces, taken from the 1D mesh and chained into
// rings as the domain's boundary is, each edge with the part of its curve on the domain's
// boundary (none on an interface). The domain is their union; a curve that two regions share
// is an interface between them ("inner/outer", a Crack with left and right), both regions'
// polygons running through the same nodes along it, unless read_gmsh_domain's `interfaces` is
// false (Domain::from_file passes RegionOptions::interfaces), when it stays inside the domain.
// from_regions's rules apply: an interface runs from boundary to boundary or closes on itself
// (round a region enclosed by another, an inclusion). Without physical
// surfaces the domain has no regions. Cracks (below) come on top of the regions and their
// interfaces, which they may not meet. meshes/two_layer_cylinder.geo is an example.
//
// Cracks (Domain::with_cracks): curves embedded in a surface (Curve{c} In Surface{s}; or an
// OpenCASCADE BooleanFragments of a surface and a line) that belong to a physical curve. The
// line elements of the crack curves are chained across curves into one polyline per connected
// line of curves, running the way its lowest-numbered curve runs; its name is its physical
// curve's (its number for a group without a name), and several physical curves give several
// cracks, in group order. An end on the boundary (a point shared with a boundary curve, or on a
// straight boundary edge) is a mouth, an end inside a tip. A .msh file records no embedding, so
// there a curve of a physical group that bounds no surface is a crack as well (the .msh gmsh
// writes from a .geo with an embedded physical curve reads as that .geo); free curves in no
// physical group that are not embedded are ignored (construction lines). InputErrors naming the
// file and the curves: an embedded curve in no physical curve (an embedded curve is never taken
// silently: name it, or remove the embedding if it only guided a mesh), a closed loop (an inner
// boundary is a hole of the surface), curves that branch (more than two elements at a node),
// one line of curves in two physical curves, one physical curve holding two separate lines, and
// every refusal of Domain::with_cracks (a crack leaving the surface, crossing another, running
// along the boundary), whose message is followed by the curves of the cracks it names.
//
// gmsh runs in a child process of its own for every read (a gmsh session there: initialise,
// read, finalise), which sends the boundary (of each region) and the crack curves back through
// a pipe: gmsh's
// global state never enters this process (reads from several threads, or beside a program's
// own gmsh session, are safe), and a file that crashes libgmsh (tests/fuzz/known_crashes) ends
// as an InputError naming the file and the signal instead of a crash. gmsh prints nothing; OpenCASCADE's STEP
// parser may still print its own syntax errors to standard output.
//
// The child runs under limits (mfree/core/child_process.hpp): wall time, 60 s by default, and
// memory (resident memory beyond what it inherits from this process), by default the lesser
// of 2 GiB and half the machine's available memory. A boundary of 400 000 line elements takes
// gmsh 0.4 s and 150 MiB (a unit square meshed at size 1e-5), so the limits refuse only files
// that would not end (an endless For loop, Include "/dev/zero";) or element sizes far too small
// for the domain, which would otherwise hang the program or exhaust the machine. A reader
// killed from outside (SIGKILL, as by the system's out-of-memory killer) is an Error, not a
// malformed file.

#include <array>
#include <chrono>
#include <cstddef>
#include <filesystem>
#include <string_view>

#include "mfree/geometry/domain.hpp"

namespace mfree {

/// File extensions read by read_gmsh_domain (lower case; matched without regard to case).
inline constexpr std::array<std::string_view, 7> gmsh_extensions = {".geo",  ".msh", ".step", ".stp",
                                                                    ".brep", ".iges", ".igs"};

/// Whether the path's extension is one of gmsh_extensions (without regard to case).
[[nodiscard]] bool is_gmsh_file(const std::filesystem::path& file);

/// Limits of the gmsh reader's child process (see above).
struct GmshReaderLimits {
  std::chrono::milliseconds wall_time;
  std::size_t memory_bytes;  // resident memory beyond what the child inherits
};

/// 60 s, and the lesser of 2 GiB and half of available_memory() (mfree/core/memory.hpp) now.
[[nodiscard]] GmshReaderLimits default_gmsh_reader_limits();

/// Reads the domain of a gmsh file (see above); `interfaces` false leaves the curves that
/// regions share inside the domain instead of making them interfaces. Throws InputError naming
/// the file when the extension is not one of gmsh_extensions, the file is missing or
/// unreadable, gmsh reports an error (its messages are quoted), the model has no surface or has
/// volumes, a node lies off the plane z = 0, a boundary or interface curve has no 1D elements,
/// a curve belongs to two physical groups, the boundary does not close into rings (or meets
/// itself), the surfaces form more than one connected region, the rings fail
/// Domain::from_rings's checks; with physical surfaces, when a surface is in none of them or in
/// two, a region's boundary does not close into rings (or meets itself), a region's surfaces
/// form more than one connected piece, or the regions fail Domain::from_regions's checks; when
/// the embedded curves are not cracks (see above), gmsh crashes on the file, or gmsh exceeds a
/// limit (naming it). Throws Error when the reader process is killed from outside (as by the
/// system's out-of-memory killer) or fails.
[[nodiscard]] Domain read_gmsh_domain(const std::filesystem::path& file,
                                      const GmshReaderLimits& limits = default_gmsh_reader_limits(),
                                      bool interfaces = true);

}  // namespace mfree
