#pragma once
// Output for ParaView: point clouds and triangulations with fields at their points, as VTK
// XML unstructured grids (.vtu, binary appended data, LZ4-compressed), fields on uniform 2D
// grids as VTK XML image data (.vti, likewise), and ParaView collections (.pvd) that string
// such files into a time series.
//
// Points are 2D (the files hold them with z = 0) or 3D (solids). Values are written as 64-bit floats, so a
// file read back gives every value bit for bit. NaN and infinity are never written: a field
// or point holding one is a NumericalError naming the field (or "point coordinates") and the
// first bad point index, and no file is touched.
//
// Every file is written atomically (see atomic_file.hpp): to a temporary file in the same
// folder, then renamed over the target; on failure the temporary file is removed and the
// target is left as it was. Missing parent folders are created.
//
// VTK's headers stay in the source file; this header needs none.

#include <array>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "mfree/core/types.hpp"

namespace mfree {

/// One named point-data array: `components` values per point, point after point
/// (values.size() == components * number of points). The count decides how it is written:
///   1  a scalar;
///   2  a 2D vector, written as a 3-component VTK vector with z = 0 so ParaView can warp by it;
///   3  a symmetric 2D tensor in the order xx, yy, xy, written as 3 components named xx, yy, xy;
///   any other count >= 1: written as given.
/// On 3D points: 3 components are a vector, 6 a symmetric tensor in the order xx, yy, zz, yz,
/// xz, xy (components so named), any other count as given.
/// Names must be non-empty and distinct within one file.
struct PointField {
  std::string name;
  int components = 1;
  std::vector<double> values;
};

/// Writes the points as an unstructured grid of VTK_VERTEX cells, one per point.
/// Throws InputError for a field of the wrong size, an empty or repeated name or a component
/// count below 1; NumericalError for a non-finite value; Error when the file cannot be
/// written. Every message names the path.
void write_point_cloud_vtu(const std::filesystem::path& path, const std::vector<Vec2>& points,
                           const std::vector<PointField>& fields);
void write_point_cloud_vtu(const std::filesystem::path& path, const std::vector<Vec3>& points,
                           const std::vector<PointField>& fields);

/// Writes the triangles (three indices into `points` each) as VTK_TRIANGLE cells with the
/// fields at the points. Errors as write_point_cloud_vtu, plus InputError for an index
/// outside [0, points.size()).
void write_triangles_vtu(const std::filesystem::path& path, const std::vector<Vec2>& points,
                         const std::vector<std::array<Index, 3>>& triangles,
                         const std::vector<PointField>& fields);
/// The same in space (a solid's surface).
void write_triangles_vtu(const std::filesystem::path& path, const std::vector<Vec3>& points,
                         const std::vector<std::array<Index, 3>>& triangles,
                         const std::vector<PointField>& fields);
/// Writes the tetrahedra (four indices into `points` each) as VTK_TETRA cells with the fields
/// at the points. Errors as write_triangles_vtu.
void write_tetrahedra_vtu(const std::filesystem::path& path, const std::vector<Vec3>& points,
                          const std::vector<std::array<Index, 4>>& tetrahedra,
                          const std::vector<PointField>& fields);

/// Writes the quadrilaterals (four indices into `points` each, counter-clockwise) as VTK_QUAD
/// cells with the fields at the points. Errors as write_triangles_vtu.
void write_quads_vtu(const std::filesystem::path& path, const std::vector<Vec2>& points,
                     const std::vector<std::array<Index, 4>>& quads, const std::vector<PointField>& fields);

/// Writes a ParaView collection of time steps: (time, file name relative to the folder of
/// the .pvd), in the given order. Throws NumericalError for a non-finite time, InputError for
/// an empty file name, Error when the file cannot be written.
void write_pvd(const std::filesystem::path& path,
               const std::vector<std::pair<double, std::string>>& steps);

/// Writes fields on a uniform 2D grid of nx x ny points, the first at `origin`, `spacing`
/// apart in both directions, as VTK XML image data (.vti): binary appended, LZ4, like the
/// .vtu files. Point fields follow the PointField conventions above, with the points in
/// grid order, x fastest: point (i, j) has index i + nx j.
/// Errors as write_point_cloud_vtu (fields of the wrong size, non-finite values, failed
/// writes), plus InputError for nx or ny below 1 or a spacing that is not positive and finite,
/// and NumericalError for a non-finite origin. Written atomically.
void write_image_vti(const std::filesystem::path& path, const Vec2& origin, double spacing,
                     int nx, int ny, const std::vector<PointField>& fields);

/// What read_vti finds in a .vti file.
struct VtiContents {
  Vec2 origin = Vec2::Zero();                       ///< position of the first point
  double spacing = 0.0;                             ///< distance between neighbouring points
  int nx = 0, ny = 0;                               ///< points along x and y
  std::vector<std::string> array_names;             ///< point-data arrays in file order
  std::map<std::string, std::vector<double>> arrays;  ///< values point after point, x fastest
  std::map<std::string, int> components;            ///< components per point of each array
};

/// Reads a 2D .vti file (one layer of points, square cells) for tests and tools. A missing,
/// unreadable or invalid file, or one that is not such an image, is an InputError naming
/// the path.
VtiContents read_vti(const std::filesystem::path& path);

/// What read_vtu finds in a .vtu file.
struct VtuContents {
  std::vector<Vec2> points;                         ///< x, y of every point
  std::vector<double> z;                            ///< z of every point
  std::vector<std::string> array_names;             ///< point-data arrays in file order
  std::map<std::string, std::vector<double>> arrays;  ///< values point after point
  std::map<std::string, int> components;            ///< components per point of each array
  Index cells = 0;                                  ///< number of cells of any type
};

/// Reads a .vtu file (any data mode) for tests and tools. A missing, unreadable or invalid
/// file is an InputError naming the path.
VtuContents read_vtu(const std::filesystem::path& path);

}  // namespace mfree
