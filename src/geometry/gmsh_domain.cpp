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
#include <set>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "gmsh_reader.hpp"
#include "mfree/core/error.hpp"
#include "mfree/core/memory.hpp"
#include "mfree/geometry/polygon_integrals.hpp"

namespace mfree {

namespace {

using gmsh_reader::lower_case;
using gmsh_reader::put;
using gmsh_reader::quoted_list;

/// One line element of the boundary of the domain or of a region: its end nodes (gmsh node
/// tags), its part and its region. An element two regions share appears once for each.
struct BoundaryEdge {
  std::size_t a;
  std::size_t b;
  int part;    // index into BoundaryMesh::part_names, -1: none (and on an interface)
  int region;  // index into BoundaryMesh::region_names, -1: the file has no physical surface
};

/// One line element of a crack curve: its end nodes, its curve (gmsh tag) and its name.
struct CrackEdge {
  std::size_t a;
  std::size_t b;
  int curve;
  int name;  // index into BoundaryMesh::crack_names, -1: the curve is in no physical group
};

/// What is read from gmsh: the line elements of the boundary (of each region, when the file
/// has physical surfaces) and of the crack curves, and the coordinates of their nodes.
struct BoundaryMesh {
  std::vector<BoundaryEdge> edges;
  std::unordered_map<std::size_t, Vec2> nodes;
  std::vector<std::string> part_names;
  std::vector<std::string> region_names;  // the physical surfaces, by group tag
  std::vector<CrackEdge> crack_edges;    // per crack curve, its elements in the curve's order
  std::vector<std::string> crack_names;  // physical names of the crack curves, by group tag
};

/// "curve 5" or "curves 5, 6 and 9" for kind "curve".
std::string tag_list(std::string_view kind, const std::vector<int>& tags) {
  std::string out = fmt::format("{}{} ", kind, tags.size() == 1 ? "" : "s");
  for (std::size_t i = 0; i < tags.size(); ++i)
    out += fmt::format("{}{}", i == 0 ? "" : (i + 1 == tags.size() ? " and " : ", "), tags[i]);
  return out;
}

/// The regions of the model: its dim-2 physical groups ("Physical Surface"), named by group
/// (by number for a group without a name) and numbered by group tag; groups of one name are
/// one region. Returns the surfaces of each region, none when the model has no physical
/// surface. Throws InputError when a surface is in no group, or in groups of two names.
std::vector<gmsh::vectorpair> surface_regions(const gmsh::vectorpair& surfaces,
                                              std::vector<std::string>& region_names,
                                              const std::string& source) {
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups, 2);
  std::map<int, std::string> name_of_group;  // ordered by tag
  for (const auto& [dim, group] : groups) {
    std::string name;
    gmsh::model::getPhysicalName(2, group, name);
    name_of_group[group] = name.empty() ? std::to_string(group) : name;
  }
  for (const auto& [group, name] : name_of_group)
    if (std::find(region_names.begin(), region_names.end(), name) == region_names.end())
      region_names.push_back(name);
  std::vector<gmsh::vectorpair> out(region_names.size());
  if (out.empty()) return out;
  std::vector<int> orphans;
  for (const auto& [dim, surface] : surfaces) {
    std::vector<int> tags;
    gmsh::model::getPhysicalGroupsForEntity(2, surface, tags);
    std::vector<std::string> names;
    for (int g : tags) names.push_back(name_of_group.at(g));
    std::sort(names.begin(), names.end());
    names.erase(std::unique(names.begin(), names.end()), names.end());
    if (names.empty()) {
      orphans.push_back(surface);
      continue;
    }
    if (names.size() > 1)
      throw InputError(
          fmt::format("{}: surface {} belongs to the physical surfaces {}; a surface belongs to "
                      "one region (physical surface) only",
                      source, surface, quoted_list(names)));
    out[std::find(region_names.begin(), region_names.end(), names[0]) - region_names.begin()].emplace_back(
        2, surface);
  }
  if (!orphans.empty())
    throw InputError(fmt::format(
        "{}: {} belong{} to no physical surface; the physical surfaces ({}) are the regions of the "
        "domain and every surface belongs to one: add {} to one",
        source, tag_list("surface", orphans), orphans.size() == 1 ? "s" : "", quoted_list(region_names),
        orphans.size() == 1 ? "it" : "them"));
  return out;
}

/// The end nodes of the line elements of a curve, in the curve's order. gmsh lists an
/// element's end (primary) nodes first, then its higher-order nodes.
std::vector<std::pair<std::size_t, std::size_t>> curve_elements(int curve) {
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> element_tags, node_tags;
  gmsh::model::mesh::getElements(types, element_tags, node_tags, 1, curve);
  std::vector<std::pair<std::size_t, std::size_t>> out;
  for (std::size_t t = 0; t < types.size(); ++t) {
    std::string name;
    int element_dim = 0, order = 0, nodes_per_element = 0, primary = 0;
    std::vector<double> local;
    gmsh::model::mesh::getElementProperties(types[t], name, element_dim, order, nodes_per_element, local,
                                            primary);
    const std::vector<std::size_t>& n = node_tags[t];
    for (std::size_t e = 0; e + nodes_per_element <= n.size(); e += nodes_per_element)
      out.emplace_back(n[e], n[e + 1]);
  }
  return out;
}

/// The curves read as cracks: those embedded in a surface (Curve{c} In Surface{s};) and the
/// curves of physical groups that bound no surface and are embedded in none, since a .msh file
/// does not record embedding. Other free curves (construction lines without a group) are left
/// out, as before cracks were read.
gmsh::vectorpair crack_curves(const gmsh::vectorpair& surfaces, const gmsh::vectorpair& curves) {
  std::set<int> tags;
  for (const auto& [dim, surface] : surfaces) {
    gmsh::vectorpair embedded;
    gmsh::model::mesh::getEmbedded(2, surface, embedded);
    for (const auto& [d, tag] : embedded)
      if (d == 1) tags.insert(tag);
  }
  for (const auto& [dim, curve] : curves) {
    std::vector<int> up, down, groups;
    gmsh::model::getAdjacencies(1, curve, up, down);
    gmsh::model::getPhysicalGroupsForEntity(1, curve, groups);
    if (up.empty() && !groups.empty()) tags.insert(curve);
  }
  gmsh::vectorpair out;
  for (int tag : tags) out.emplace_back(1, tag);
  return out;
}

/// Opens the file in the current gmsh session and reads the boundary of its surfaces and the
/// crack curves: line elements (meshing the curves first when the file has no 1D mesh), nodes
/// and parts.
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
  const std::map<int, int> part =
      gmsh_reader::entity_parts(1, boundary, mesh.part_names, file, "boundary curve");
  // With physical surfaces, the boundary of each region (its curves bounding exactly one of its
  // surfaces): the domain's boundary curves with their parts, and the interfaces, which two
  // regions share and which carry no part.
  const std::vector<gmsh::vectorpair> regions = surface_regions(surfaces, mesh.region_names, file);
  std::vector<gmsh::vectorpair> region_boundaries;
  if (regions.empty()) region_boundaries.push_back(boundary);
  for (const gmsh::vectorpair& region : regions)
    gmsh::model::getBoundary(region, region_boundaries.emplace_back(), /*combined=*/true, /*oriented=*/false,
                             /*recursive=*/false);
  const bool is_msh = lower_case(std::filesystem::path(file).extension().string()) == ".msh";
  for (std::size_t r = 0; r < region_boundaries.size(); ++r) {
    const int region = regions.empty() ? -1 : static_cast<int>(r);
    for (const auto& [dim, curve] : region_boundaries[r]) {
      const auto on_boundary = part.find(curve);
      const int curve_part = on_boundary == part.end() ? -1 : on_boundary->second;
      const auto elements = curve_elements(curve);
      for (const auto& [a, b] : elements) mesh.edges.push_back(BoundaryEdge{a, b, curve_part, region});
      if (elements.empty()) {
        const std::string_view kind = on_boundary == part.end() ? "interface curve" : "boundary curve";
        throw InputError(fmt::format(
            "{}: {} {} has no 1D mesh elements{}", file, kind, curve,
            is_msh
                ? fmt::format(" (a .msh file holds only the elements of physical groups unless written with "
                              "Mesh.SaveAll = 1: put every {} in a physical curve)",
                              kind)
                : ""));
      }
    }
  }
  const gmsh::vectorpair cracks = crack_curves(surfaces, curves);
  const std::map<int, int> crack_name =
      gmsh_reader::entity_parts(1, cracks, mesh.crack_names, file, "embedded curve");
  for (const auto& [dim, curve] : cracks) {
    const auto elements = curve_elements(curve);
    for (const auto& [a, b] : elements)
      mesh.crack_edges.push_back(CrackEdge{a, b, curve, crack_name.at(curve)});
    if (elements.empty())
      throw InputError(fmt::format("{}: embedded curve {} has no 1D mesh elements", file, curve));
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
// (nodes: tag, x, y; edges: a, b, part, region; part names; region names; crack edges: a, b,
// curve, name; crack names), or 'E' and an error message. Counts are std::size_t, names their
// length and bytes.

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
  gmsh_reader::put_names(out, mesh.part_names);
  gmsh_reader::put_names(out, mesh.region_names);
  put(out, mesh.crack_edges.size());
  for (const CrackEdge& e : mesh.crack_edges) put(out, e);
  gmsh_reader::put_names(out, mesh.crack_names);
  return out;
}

BoundaryMesh deserialise(const std::string& bytes, const std::string& file) {
  gmsh_reader::MessageReader in(bytes, file);
  BoundaryMesh mesh;
  for (std::size_t k = 0, n = in.count(); k < n; ++k) {
    const auto tag = in.take<std::size_t>();
    const auto x = in.take<double>();
    const auto y = in.take<double>();
    mesh.nodes.emplace(tag, Vec2(x, y));
  }
  mesh.edges.resize(in.count());
  for (BoundaryEdge& e : mesh.edges) e = in.take<BoundaryEdge>();
  mesh.part_names = in.names();
  mesh.region_names = in.names();
  mesh.crack_edges.resize(in.count());
  for (CrackEdge& e : mesh.crack_edges) e = in.take<CrackEdge>();
  mesh.crack_names = in.names();
  in.finish();
  const int regions = static_cast<int>(mesh.region_names.size());
  const bool regions_known = std::all_of(mesh.edges.begin(), mesh.edges.end(), [&](const BoundaryEdge& e) {
    return regions == 0 ? e.region == -1 : e.region >= 0 && e.region < regions;
  });
  if (!regions_known) throw Error(fmt::format("{}: the gmsh reader process sent a malformed mesh", file));
  return mesh;
}

/// Closed rings from boundary edges: every node must end exactly two edges. Returns the
/// rings (vertices in chain order) and, per ring, the part of edge i (vertex i to i + 1).
std::pair<std::vector<Ring>, std::vector<std::vector<int>>> chain_rings(
    const std::vector<BoundaryEdge>& edges, const std::unordered_map<std::size_t, Vec2>& nodes,
    const std::string& source) {
  std::unordered_map<std::size_t, std::vector<std::size_t>> edges_at;  // node -> its edges
  for (std::size_t e = 0; e < edges.size(); ++e) {
    edges_at[edges[e].a].push_back(e);
    edges_at[edges[e].b].push_back(e);
  }
  // Report the lowest offending node, so that the message does not depend on hash order.
  std::size_t worst = 0;
  for (const auto& [node, at] : edges_at)
    if (at.size() != 2 && (worst == 0 || node < worst)) worst = node;
  if (worst != 0) {
    const Vec2& x = nodes.at(worst);
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
  std::vector<bool> used(edges.size(), false);
  for (std::size_t first = 0; first < edges.size(); ++first) {
    if (used[first]) continue;
    Ring ring;
    std::vector<int> ring_parts;
    const std::size_t start = edges[first].a;
    std::size_t node = start;
    std::size_t edge = first;
    do {
      used[edge] = true;
      const BoundaryEdge& e = edges[edge];
      ring.push_back(nodes.at(node));
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

/// Puts the outer ring first. A ring inside an even number of others bounds a piece from
/// outside; there must be exactly one such ring (one connected domain, or region when
/// `region`).
void outer_ring_first(std::vector<Ring>& rings, std::vector<std::vector<int>>& parts,
                      const std::string& source, bool region) {
  std::vector<std::size_t> outer;
  for (std::size_t i = 0; i < rings.size(); ++i) {
    int depth = 0;
    for (std::size_t j = 0; j < rings.size(); ++j) depth += j != i && inside(rings[j], rings[i][0]);
    if (depth % 2 == 0) outer.push_back(i);
  }
  if (outer.size() != 1) {
    std::string found;
    for (std::size_t i : outer) found += fmt::format("{}{}", found.empty() ? "" : ", ", describe(rings[i]));
    throw InputError(
        region
            ? fmt::format("{}: its surfaces form {} disconnected pieces, with outer boundaries in the boxes "
                          "{}; a physical surface is one connected region (holes allowed): give each "
                          "piece a physical surface of its own",
                          source, outer.size(), found)
            : fmt::format("{}: the surfaces form {} disconnected regions, with outer boundaries in "
                          "the boxes {}; mfree reads one connected domain (holes allowed)",
                          source, outer.size(), found));
  }
  std::swap(rings[0], rings[outer[0]]);
  std::swap(parts[0], parts[outer[0]]);
}

/// The domain of a file without physical surfaces: the polygon of its boundary.
Domain one_polygon(const BoundaryMesh& mesh, const std::string& source) {
  auto [rings, parts] = chain_rings(mesh.edges, mesh.nodes, source);
  outer_ring_first(rings, parts, source, /*region=*/false);
  return Domain::from_rings(std::move(rings), std::move(parts), mesh.part_names, source);
}

/// The domain of a file with physical surfaces: the union of its regions (Domain::from_regions),
/// the polygon of each chained from the line elements of its boundary.
Domain union_of_regions(const BoundaryMesh& mesh, const std::string& source, bool interfaces) {
  std::vector<std::vector<BoundaryEdge>> edges(mesh.region_names.size());
  for (const BoundaryEdge& e : mesh.edges) edges[e.region].push_back(e);
  std::vector<std::vector<Ring>> polygons;
  std::vector<std::vector<std::vector<int>>> parts;
  for (std::size_t r = 0; r < edges.size(); ++r) {
    const std::string where = fmt::format("{}, physical surface '{}'", source, mesh.region_names[r]);
    auto [rings, ring_parts] = chain_rings(edges[r], mesh.nodes, where);
    outer_ring_first(rings, ring_parts, where, /*region=*/true);
    polygons.push_back(std::move(rings));
    parts.push_back(std::move(ring_parts));
  }
  return Domain::from_regions(std::move(polygons), RegionOptions{mesh.region_names, interfaces}, source,
                              std::move(parts), mesh.part_names);
}

/// A crack chained from the line elements of its curves: its vertices in order, its name and
/// its curves (gmsh tags, ascending).
struct CrackChain {
  std::vector<Vec2> points;
  std::string name;
  std::vector<int> curves;
};

/// The crack edges of one connected set of crack curves, and its end nodes (the nodes that end
/// one edge; none for a closed loop).
struct CrackComponent {
  std::vector<std::size_t> edges;  // indices into BoundaryMesh::crack_edges
  std::vector<std::size_t> ends;
  std::vector<int> curves;  // ascending
};

/// Splits the crack edges into connected components; throws InputError where more than two
/// edges meet (a branching network).
std::vector<CrackComponent> crack_components(const BoundaryMesh& mesh, const std::string& source) {
  const std::vector<CrackEdge>& edges = mesh.crack_edges;
  // node -> its edges; ordered, so that the lowest offending node is the one reported
  std::map<std::size_t, std::vector<std::size_t>> edges_at;
  for (std::size_t e = 0; e < edges.size(); ++e) {
    edges_at[edges[e].a].push_back(e);
    edges_at[edges[e].b].push_back(e);
  }
  for (const auto& [node, at] : edges_at) {
    if (at.size() <= 2) continue;
    std::set<int> curves;
    for (std::size_t e : at) curves.insert(edges[e].curve);
    const Vec2& x = mesh.nodes.at(node);
    throw InputError(fmt::format(
        "{}: embedded {}: a branch point at ({}, {}) (node {}, where {} of their line elements end); "
        "a crack is one unbranched line and cracks do not touch: make the branches separate cracks that "
        "do not meet",
        source, tag_list("curve", {curves.begin(), curves.end()}), x.x(), x.y(), node, at.size()));
  }
  std::vector<CrackComponent> out;
  std::vector<bool> seen(edges.size(), false);
  for (std::size_t first = 0; first < edges.size(); ++first) {
    if (seen[first]) continue;
    CrackComponent c;
    std::set<int> curves;
    std::vector<std::size_t> stack{first};
    seen[first] = true;
    while (!stack.empty()) {
      const std::size_t e = stack.back();
      stack.pop_back();
      c.edges.push_back(e);
      curves.insert(edges[e].curve);
      for (const std::size_t node : {edges[e].a, edges[e].b}) {
        const std::vector<std::size_t>& at = edges_at.at(node);
        if (at.size() == 1) c.ends.push_back(node);
        for (std::size_t f : at)
          if (!seen[f]) {
            seen[f] = true;
            stack.push_back(f);
          }
      }
    }
    c.curves.assign(curves.begin(), curves.end());
    out.push_back(std::move(c));
  }
  return out;
}

/// The vertices of an open component from one end to the other, running the way its
/// lowest-numbered curve runs: the way that curve's first element (gmsh orders a curve's
/// elements along it) goes from its node a to its node b.
std::vector<Vec2> walk(const BoundaryMesh& mesh, const CrackComponent& c) {
  std::unordered_map<std::size_t, std::vector<std::size_t>> edges_at;
  std::size_t guide = mesh.crack_edges.size();  // the first element of the lowest curve
  for (std::size_t e : c.edges) {
    edges_at[mesh.crack_edges[e].a].push_back(e);
    edges_at[mesh.crack_edges[e].b].push_back(e);
    if (mesh.crack_edges[e].curve == c.curves[0]) guide = std::min(guide, e);
  }
  std::vector<std::size_t> nodes{c.ends[0]};
  bool backwards = false;
  for (std::size_t edge = edges_at.at(c.ends[0])[0];;) {
    const CrackEdge& e = mesh.crack_edges[edge];
    const std::size_t next = e.a == nodes.back() ? e.b : e.a;
    if (edge == guide) backwards = next == e.a;
    nodes.push_back(next);
    const std::vector<std::size_t>& at = edges_at.at(next);
    if (at.size() == 1) break;
    edge = at[0] == edge ? at[1] : at[0];
  }
  if (backwards) std::reverse(nodes.begin(), nodes.end());
  std::vector<Vec2> points;
  for (std::size_t n : nodes) points.push_back(mesh.nodes.at(n));
  return points;
}

/// The cracks of the mesh, one per connected set of crack curves, in the order of their
/// physical groups. Throws InputError naming the curves when a set branches, closes into a
/// loop, has a curve in no physical group or curves of two groups, or when two sets share one
/// name.
std::vector<CrackChain> chain_cracks(const BoundaryMesh& mesh, const std::string& source) {
  std::map<int, CrackChain> by_name;  // name index -> its crack
  for (const CrackComponent& c : crack_components(mesh, source)) {
    if (c.ends.empty()) {
      const Vec2& x = mesh.nodes.at(mesh.crack_edges[c.edges[0]].a);
      throw InputError(fmt::format(
          "{}: embedded {}: a closed loop through ({}, {}); a crack is an open line with two ends. "
          "An inner boundary is a hole: put its curve loop in the surface (Plane Surface(s) = {{outer, "
          "hole}};) instead of embedding it",
          source, tag_list("curve", c.curves), x.x(), x.y()));
    }
    std::set<int> names;
    for (std::size_t e : c.edges) {
      const CrackEdge& edge = mesh.crack_edges[e];
      if (edge.name < 0)
        throw InputError(fmt::format(
            "{}: embedded curve {} belongs to no physical curve; an embedded curve is read as a crack "
            "named by its physical curve: add it to one (Physical Curve(\"crack\") = {{{}}};) or remove "
            "it from the surface",
            source, edge.curve, edge.curve));
      names.insert(edge.name);
    }
    if (names.size() > 1)
      throw InputError(
          fmt::format("{}: embedded {}: one line in the physical curves '{}' and '{}'; "
                      "a crack has one name: put its curves in one physical curve",
                      source, tag_list("curve", c.curves), mesh.crack_names[*names.begin()],
                      mesh.crack_names[*std::next(names.begin())]));
    const int name = *names.begin();
    if (const auto other = by_name.find(name); other != by_name.end())
      throw InputError(
          fmt::format("{}: the physical curve '{}' holds two separate lines (embedded {} and {}); "
                      "a crack is one line: give each its own physical curve",
                      source, mesh.crack_names[name], tag_list("curve", other->second.curves),
                      tag_list("curve", c.curves)));
    by_name[name] = CrackChain{walk(mesh, c), mesh.crack_names[name], c.curves};
  }
  std::vector<CrackChain> out;
  for (auto& [name, chain] : by_name) out.push_back(std::move(chain));
  return out;
}

/// The domain with the cracks (Domain::with_cracks); its InputErrors also name the gmsh curves
/// of the cracks they name.
Domain with_gmsh_cracks(const Domain& domain, std::vector<CrackChain> chains, const std::string& source) {
  std::vector<std::vector<Vec2>> lines;
  std::vector<std::string> names;
  for (CrackChain& c : chains) {
    lines.push_back(std::move(c.points));
    names.push_back(c.name);
  }
  try {
    return domain.with_cracks(std::move(lines), std::move(names), source);
  } catch (const InputError& e) {
    std::string message = e.what(), curves;
    for (const CrackChain& c : chains)
      if (message.find(fmt::format("crack '{}'", c.name)) != std::string::npos ||
          message.find(fmt::format("crack name '{}'", c.name)) != std::string::npos)
        curves += fmt::format("{}crack '{}' is the embedded {}", curves.empty() ? "" : ", ", c.name,
                              tag_list("curve", c.curves));
    throw InputError(curves.empty() ? message : fmt::format("{} ({})", message, curves));
  }
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

Domain read_gmsh_domain(const std::filesystem::path& file, const GmshReaderLimits& limits, bool interfaces) {
  const std::string source = file.string();
  gmsh_reader::check_file(file);
  BoundaryMesh mesh = deserialise(
      gmsh_reader::read_in_child(source, limits, [&source] { return serialise(read_boundary(source)); }),
      source);
  Domain domain =
      mesh.region_names.empty() ? one_polygon(mesh, source) : union_of_regions(mesh, source, interfaces);
  std::vector<CrackChain> cracks = chain_cracks(mesh, source);
  if (cracks.empty()) return domain;
  return with_gmsh_cracks(domain, std::move(cracks), source);
}

}  // namespace mfree
