#include "mfree/geometry/gmsh_domain.hpp"

#include <fmt/format.h>
#include <gmsh.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstddef>
#include <cstring>
#include <fstream>
#include <map>
#include <new>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "mfree/core/child_process.hpp"
#include "mfree/core/error.hpp"
#include "mfree/core/memory.hpp"
#include "mfree/geometry/polygon_integrals.hpp"

namespace mfree {

namespace {

/// One line element of the boundary: its end nodes (gmsh node tags) and its part.
struct BoundaryEdge {
  std::size_t a;
  std::size_t b;
  int part;  // index into BoundaryMesh::part_names, -1: none
};

/// What is read from gmsh: the boundary's line elements and the coordinates of their nodes.
struct BoundaryMesh {
  std::vector<BoundaryEdge> edges;
  std::unordered_map<std::size_t, Vec2> nodes;
  std::vector<std::string> part_names;
};

std::string lower_case(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

std::string accepted_extensions() {
  std::string list;
  for (const std::string_view e : gmsh_extensions) list += fmt::format("{}{}", list.empty() ? "" : ", ", e);
  return list;
}

/// One gmsh session: initialised quietly (no configuration files, nothing on the terminal),
/// its messages collected by the logger, finalised when it ends. gmsh keeps one model, one
/// option set and one logger for a whole process: a session runs in a process of its own
/// (read_isolated below).
class GmshSession {
 public:
  GmshSession() {
    gmsh::initialize(0, nullptr, /*readConfigFiles=*/false);
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::logger::start();
  }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;
  ~GmshSession() {
    // gmsh reports errors by throwing std::string; none may leave a destructor.
    try {
      gmsh::logger::stop();
      gmsh::finalize();
    } catch (...) {
    }
  }

  /// gmsh's error messages so far, joined by "; ", or `thrown` (the message gmsh threw) if
  /// the log holds none.
  [[nodiscard]] static std::string errors(const std::string& thrown) {
    std::vector<std::string> log;
    gmsh::logger::get(log);
    std::string out;
    const std::string_view prefix = "Error: ";
    for (const std::string& line : log) {
      if (line.compare(0, prefix.size(), prefix) == 0) {
        out += fmt::format("{}{}", out.empty() ? "" : "; ", line.substr(prefix.size()));
      }
    }
    return out.empty() ? thrown : out;
  }
};

/// The part index of every boundary curve (-1: none) with the part names, from the dim-1
/// physical groups. Parts are numbered by group tag; groups of the same name are one part.
std::map<int, int> curve_parts(const gmsh::vectorpair& curves, std::vector<std::string>& part_names,
                               const std::string& source) {
  std::map<int, int> group_of_curve;  // curve tag -> physical group tag, 0: none
  std::map<int, std::string> used;    // group tag -> name, groups on the boundary only
  for (const auto& [dim, curve] : curves) {
    std::vector<int> groups;
    gmsh::model::getPhysicalGroupsForEntity(1, curve, groups);
    std::vector<std::string> names;
    for (int g : groups) {
      std::string name;
      gmsh::model::getPhysicalName(1, g, name);
      names.push_back(name.empty() ? std::to_string(g) : name);
    }
    std::sort(names.begin(), names.end());
    names.erase(std::unique(names.begin(), names.end()), names.end());
    if (names.size() > 1) {
      std::string list;
      for (std::size_t i = 0; i < names.size(); ++i)
        list += fmt::format("{}'{}'", i == 0 ? "" : (i + 1 == names.size() ? " and " : ", "), names[i]);
      throw InputError(fmt::format("{}: boundary curve {} belongs to the physical curves {}; a boundary "
                                   "edge belongs to one named part only",
                                   source, curve, list));
    }
    group_of_curve[curve] = groups.empty() ? 0 : groups.front();
    if (!groups.empty()) used[groups.front()] = names.front();
  }
  std::map<int, int> part_of_group;
  for (const auto& [group, name] : used) {
    const auto known = std::find(part_names.begin(), part_names.end(), name);
    part_of_group[group] = static_cast<int>(known - part_names.begin());
    if (known == part_names.end()) part_names.push_back(name);
  }
  std::map<int, int> out;
  for (const auto& [curve, group] : group_of_curve) out[curve] = group == 0 ? -1 : part_of_group[group];
  return out;
}

/// Opens the file in the current gmsh session and reads the boundary of its surfaces: line
/// elements (meshing the curves first when the file has no 1D mesh), nodes and parts.
BoundaryMesh read_boundary(const std::string& file) {
  gmsh::open(file);

  gmsh::vectorpair surfaces, volumes, curves;
  gmsh::model::getEntities(surfaces, 2);
  gmsh::model::getEntities(volumes, 3);
  gmsh::model::getEntities(curves, 1);
  if (surfaces.empty()) {
    throw InputError(fmt::format("{}: no 2D entity (surface) to take as the domain; the file defines {} "
                                 "curves and no surface",
                                 file, curves.size()));
  }
  if (!volumes.empty()) {
    throw InputError(fmt::format("{}: the model has {} 3D volume(s); mfree reads planar domains "
                                 "(surfaces in the plane z = 0)",
                                 file, volumes.size()));
  }

  std::vector<int> types;
  std::vector<std::vector<std::size_t>> element_tags, node_tags;
  gmsh::model::mesh::getElements(types, element_tags, node_tags, 1, -1);
  if (types.empty()) gmsh::model::mesh::generate(1);

  // The boundary of the union: curves bounding exactly one surface, without orientation
  // (the rings are chained from the elements' nodes, so curve directions do not matter).
  gmsh::vectorpair boundary;
  gmsh::model::getBoundary(surfaces, boundary, /*combined=*/true, /*oriented=*/false, /*recursive=*/false);
  if (boundary.empty()) throw InputError(fmt::format("{}: the surfaces have no boundary curves", file));

  BoundaryMesh mesh;
  const std::map<int, int> part = curve_parts(boundary, mesh.part_names, file);
  const bool is_msh = lower_case(std::filesystem::path(file).extension().string()) == ".msh";
  for (const auto& [dim, curve] : boundary) {
    gmsh::model::mesh::getElements(types, element_tags, node_tags, 1, curve);
    std::size_t count = 0;
    for (std::size_t t = 0; t < types.size(); ++t) {
      std::string name;
      int element_dim = 0, order = 0, nodes_per_element = 0, primary = 0;
      std::vector<double> local;
      gmsh::model::mesh::getElementProperties(types[t], name, element_dim, order, nodes_per_element, local,
                                              primary);
      // gmsh lists an element's end (primary) nodes first, then its higher-order nodes.
      const std::vector<std::size_t>& n = node_tags[t];
      for (std::size_t e = 0; e + nodes_per_element <= n.size(); e += nodes_per_element) {
        mesh.edges.push_back(BoundaryEdge{n[e], n[e + 1], part.at(curve)});
      }
      count += element_tags[t].size();
    }
    if (count == 0) {
      throw InputError(fmt::format(
          "{}: boundary curve {} has no 1D mesh elements{}", file, curve,
          is_msh ? " (a .msh file holds only the elements of physical groups unless written with "
                   "Mesh.SaveAll = 1: put every boundary curve in a physical curve)"
                 : ""));
    }
  }

  std::vector<std::size_t> tags;
  std::vector<double> xyz, parametric;
  gmsh::model::mesh::getNodes(tags, xyz, parametric, -1, -1, /*includeBoundary=*/false,
                              /*returnParametricCoord=*/false);
  double size = 0.0;  // the largest coordinate, the scale of the z = 0 test
  for (std::size_t i = 0; i < tags.size(); ++i) size = std::max({size, std::abs(xyz[3 * i]), std::abs(xyz[3 * i + 1])});
  for (std::size_t i = 0; i < tags.size(); ++i) {
    const double x = xyz[3 * i], y = xyz[3 * i + 1], z = xyz[3 * i + 2];
    if (std::abs(z) > 1e-12 * size) {
      throw InputError(fmt::format("{}: node {} at ({}, {}, {}) is off the plane z = 0; mfree reads planar "
                                   "domains in z = 0",
                                   file, tags[i], x, y, z));
    }
    mesh.nodes.emplace(tags[i], Vec2(x, y));
  }
  return mesh;
}

// The boundary mesh through a pipe from the child process that read it: 'M' and the mesh
// (nodes: tag, x, y; edges: a, b, part; part names), or 'E' and an error message.

template <class T>
void put(std::string& out, const T& value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof(T));
}

std::string serialise(const BoundaryMesh& mesh) {
  std::string out = "M";
  put(out, mesh.nodes.size());
  for (const auto& [tag, x] : mesh.nodes) {
    put(out, tag);
    put(out, x.x());
    put(out, x.y());
  }
  put(out, mesh.edges.size());
  for (const BoundaryEdge& e : mesh.edges) put(out, e);
  put(out, mesh.part_names.size());
  for (const std::string& name : mesh.part_names) {
    put(out, name.size());
    out += name;
  }
  return out;
}

BoundaryMesh deserialise(const std::string& bytes, const std::string& file) {
  std::size_t at = 1;
  const auto take = [&](void* to, std::size_t n) {
    if (n > bytes.size() - at) throw Error(fmt::format("{}: the gmsh reader process sent a truncated mesh", file));
    std::memcpy(to, bytes.data() + at, n);
    at += n;
  };
  const auto count = [&] {
    std::size_t n;
    take(&n, sizeof n);
    if (n > bytes.size()) throw Error(fmt::format("{}: the gmsh reader process sent a malformed mesh", file));
    return n;
  };
  BoundaryMesh mesh;
  for (std::size_t k = 0, n = count(); k < n; ++k) {
    std::size_t tag;
    double x, y;
    take(&tag, sizeof tag);
    take(&x, sizeof x);
    take(&y, sizeof y);
    mesh.nodes.emplace(tag, Vec2(x, y));
  }
  mesh.edges.resize(count());
  for (BoundaryEdge& e : mesh.edges) take(&e, sizeof e);
  mesh.part_names.resize(count());
  for (std::string& name : mesh.part_names) {
    name.resize(count());
    take(name.data(), name.size());
  }
  return mesh;
}

/// What the child process sends: the serialised mesh, or 'E' and an error message.
std::string read_boundary_message(const std::string& file) {
  try {
    const GmshSession session;
    try {
      return serialise(read_boundary(file));
    } catch (const std::string& thrown) {
      return "E" + fmt::format("{}: gmsh cannot read it: {}", file, GmshSession::errors(thrown));
    }
  } catch (const std::bad_alloc&) {
    return "E" + fmt::format(
                     "{}: gmsh ran out of memory reading it: element sizes too small for the domain "
                     "(point sizes, Mesh.MeshSizeMax) are the usual cause; coarsen them",
                     file);
  } catch (const std::exception& e) {
    return std::string("E") + e.what();
  } catch (...) {
    return "E" + fmt::format("{}: gmsh cannot read it", file);
  }
}

/// Whether a signal is one a crash raises (rather than one sent from outside).
bool is_crash_signal(int signal) {
  for (const int crash : {SIGSEGV, SIGBUS, SIGABRT, SIGFPE, SIGILL, SIGSYS, SIGTRAP})
    if (signal == crash) return true;
  return false;
}

/// read_boundary in a child process (mfree/core/child_process.hpp) under the limits: libgmsh
/// crashes on some malformed files (tests/fuzz/known_crashes), loops forever on others and
/// may exhaust the memory; each must end as an error naming the file, not take the program
/// down. gmsh's global state also stays out of this process, so reads from several threads
/// need no lock.
BoundaryMesh read_isolated(const std::string& file, const GmshReaderLimits& limits) {
  const ChildOutcome out = run_in_child([&file] { return read_boundary_message(file); },
                                        ChildLimits{limits.wall_time, limits.memory_bytes},
                                        fmt::format("{}: the gmsh reader", file));
  switch (out.end) {
    case ChildOutcome::End::out_of_time:
      throw InputError(fmt::format(
          "{}: gmsh did not finish reading it within {:g} s (the limit of the gmsh reader; see README): an "
          "endless loop in a .geo script, an Include of a file that never ends (such as a device) or element "
          "sizes far too small for the domain",
          file, std::chrono::duration<double>(limits.wall_time).count()));
    case ChildOutcome::End::out_of_memory:
      throw InputError(fmt::format(
          "{}: gmsh used more than {:g} MiB of memory reading it (the limit of the gmsh reader; see README): "
          "element sizes too small for the domain (point sizes, Mesh.MeshSizeMax) are the usual cause; "
          "coarsen them",
          file, static_cast<double>(limits.memory_bytes) / (1024.0 * 1024.0)));
    case ChildOutcome::End::signalled:
      if (is_crash_signal(out.code))
        throw InputError(fmt::format("{}: gmsh crashed reading it ({}): the file is malformed", file,
                                     ::strsignal(out.code)));
      throw Error(
          fmt::format("{}: the gmsh reader process was ended from outside by signal {} ({}) while "
                      "reading it{}",
                      file, out.code, ::strsignal(out.code),
                      out.code == SIGKILL ? ", most likely by the system for lack of memory (element "
                                            "sizes too small for the domain?)"
                                          : ""));
    case ChildOutcome::End::exited:
      break;
  }
  if (out.code != 0 || out.output.empty())
    throw Error(fmt::format("{}: the gmsh reader process failed (exit status {})", file, out.code));
  if (out.output[0] == 'E') throw InputError(out.output.substr(1));
  return deserialise(out.output, file);
}

/// Closed rings from the boundary edges: every node must end exactly two edges. Returns the
/// rings (vertices in chain order) and, per ring, the part of edge i (vertex i to i + 1).
std::pair<std::vector<Ring>, std::vector<std::vector<int>>> chain_rings(const BoundaryMesh& mesh,
                                                                          const std::string& source) {
  std::unordered_map<std::size_t, std::vector<std::size_t>> edges_at;  // node -> its edges
  for (std::size_t e = 0; e < mesh.edges.size(); ++e) {
    edges_at[mesh.edges[e].a].push_back(e);
    edges_at[mesh.edges[e].b].push_back(e);
  }
  // Report the lowest offending node, so that the message does not depend on hash order.
  std::size_t worst = 0;
  for (const auto& [node, at] : edges_at)
    if (at.size() != 2 && (worst == 0 || node < worst)) worst = node;
  if (worst != 0) {
    const Vec2& x = mesh.nodes.at(worst);
    const std::size_t n = edges_at.at(worst).size();
    if (n == 1) {
      throw InputError(fmt::format("{}: a boundary ring does not close: it ends at ({}, {}) (node {})", source,
                                   x.x(), x.y(), worst));
    }
    throw InputError(fmt::format("{}: the boundary meets itself at ({}, {}) (node {}, where {} boundary "
                                 "edges end); rings must not touch",
                                 source, x.x(), x.y(), worst, n));
  }

  std::vector<Ring> rings;
  std::vector<std::vector<int>> parts;
  std::vector<bool> used(mesh.edges.size(), false);
  for (std::size_t first = 0; first < mesh.edges.size(); ++first) {
    if (used[first]) continue;
    Ring ring;
    std::vector<int> ring_parts;
    const std::size_t start = mesh.edges[first].a;
    std::size_t node = start;
    std::size_t edge = first;
    do {
      used[edge] = true;
      const BoundaryEdge& e = mesh.edges[edge];
      ring.push_back(mesh.nodes.at(node));
      ring_parts.push_back(e.part);
      node = e.a == node ? e.b : e.a;
      const std::vector<std::size_t>& at = edges_at.at(node);
      edge = at[0] == edge ? at[1] : at[0];
    } while (node != start);
    rings.push_back(std::move(ring));
    parts.push_back(std::move(ring_parts));
  }
  return {std::move(rings), std::move(parts)};
}

/// Whether x lies inside the ring (crossing number; x is not on the ring).
bool inside(const Ring& ring, const Vec2& x) {
  bool in = false;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
    const Vec2& p = ring[i];
    const Vec2& q = ring[j];
    if ((p.y() > x.y()) != (q.y() > x.y()) &&
        x.x() < p.x() + (x.y() - p.y()) * (q.x() - p.x()) / (q.y() - p.y()))
      in = !in;
  }
  return in;
}

std::string describe(const Ring& ring) {
  const Box b = ring_bounding_box(ring);
  return fmt::format("[{}, {}] x [{}, {}]", b.lo.x(), b.hi.x(), b.lo.y(), b.hi.y());
}

/// Puts the outer ring first. A ring inside an even number of others bounds a region from
/// outside; there must be exactly one such ring (one connected domain).
void outer_ring_first(std::vector<Ring>& rings, std::vector<std::vector<int>>& parts, const std::string& source) {
  std::vector<std::size_t> outer;
  for (std::size_t i = 0; i < rings.size(); ++i) {
    int depth = 0;
    for (std::size_t j = 0; j < rings.size(); ++j) depth += j != i && inside(rings[j], rings[i][0]);
    if (depth % 2 == 0) outer.push_back(i);
  }
  if (outer.size() != 1) {
    std::string found;
    for (std::size_t i : outer) found += fmt::format("{}{}", found.empty() ? "" : ", ", describe(rings[i]));
    throw InputError(fmt::format("{}: the surfaces form {} disconnected regions, with outer boundaries in "
                                 "the boxes {}; mfree reads one connected domain (holes allowed)",
                                 source, outer.size(), found));
  }
  std::swap(rings[0], rings[outer[0]]);
  std::swap(parts[0], parts[outer[0]]);
}

}  // namespace

bool is_gmsh_file(const std::filesystem::path& file) {
  const std::string ext = lower_case(file.extension().string());
  return std::find(gmsh_extensions.begin(), gmsh_extensions.end(), ext) != gmsh_extensions.end();
}

GmshReaderLimits default_gmsh_reader_limits() {
  constexpr double cap = 2.0 * 1024 * 1024 * 1024;  // bytes
  return GmshReaderLimits{std::chrono::seconds(60),
                          static_cast<std::size_t>(std::min(cap, 0.5 * available_memory().bytes))};
}

Domain read_gmsh_domain(const std::filesystem::path& file, const GmshReaderLimits& limits) {
  const std::string source = file.string();
  if (!is_gmsh_file(file)) {
    throw InputError(fmt::format("{}: unknown extension '{}' for a gmsh file; gmsh files end in {}", source,
                                 file.extension().string(), accepted_extensions()));
  }
  // gmsh opens a missing file without complaint (an empty model), so look first.
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) {
    throw InputError(fmt::format("mesh file '{}' does not exist or is not a regular file", source));
  }
  if (!std::ifstream(file)) throw InputError(fmt::format("cannot read mesh file '{}'", source));

  BoundaryMesh mesh = read_isolated(source, limits);
  auto [rings, parts] = chain_rings(mesh, source);
  outer_ring_first(rings, parts, source);
  return Domain::from_rings(std::move(rings), std::move(parts), std::move(mesh.part_names), source);
}

}  // namespace mfree
