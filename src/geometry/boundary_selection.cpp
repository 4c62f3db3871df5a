#include "mfree/geometry/boundary_selection.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "mfree/core/error.hpp"
#include "mfree/geometry/convex_polygon.hpp"

namespace mfree {

namespace {

/// Whole segments s for which keep(s) holds.
template <class Keep>
BoundarySelection<2> whole_segments(const Domain& domain, Keep&& keep) {
  BoundarySelection<2> out;
  const auto& segments = domain.boundary();
  for (std::size_t s = 0; s < segments.size(); ++s)
    if (keep(segments[s])) out.push_back({static_cast<Index>(s), 0.0, 1.0});
  return out;
}

int ring_count(const Domain& domain) { return static_cast<int>(domain.rings().size()); }

}  // namespace

double selection_length(const Domain& domain, const BoundarySelection<2>& s) {
  double length = 0.0;
  for (const BoundaryPiece<2>& p : s) length += (p.t1 - p.t0) * domain.boundary()[p.segment].length;
  return length;
}

std::vector<CornerSliver> corner_slivers(const Domain& domain, const BoundarySelection<2>& s, double min_turn,
                                         double fraction) {
  // The pieces' ends; ends at the same vertex meet (segments share their vertices' values).
  struct End {
    Vec2 x;
    std::size_t piece;
    bool start;
  };
  std::vector<End> ends;
  const auto& segments = domain.boundary();
  for (std::size_t i = 0; i < s.size(); ++i) {
    const BoundarySegment& g = segments[static_cast<std::size_t>(s[i].segment)];
    ends.push_back({g.a + s[i].t0 * (g.b - g.a), i, true});
    ends.push_back({g.a + s[i].t1 * (g.b - g.a), i, false});
  }
  const auto before = [](const End& a, const End& b) {
    return a.x.x() < b.x.x() || (a.x.x() == b.x.x() && a.x.y() < b.x.y());
  };
  std::sort(ends.begin(), ends.end(), before);
  const auto length = [&](std::size_t i) {
    return (s[i].t1 - s[i].t0) * segments[static_cast<std::size_t>(s[i].segment)].length;
  };
  const auto direction = [&](std::size_t i) {
    const BoundarySegment& g = segments[static_cast<std::size_t>(s[i].segment)];
    return Vec2((g.b - g.a) / g.length);
  };
  const double cos_turn = std::cos(min_turn * std::numbers::pi / 180.0);
  std::vector<CornerSliver> out;
  for (std::size_t k = 0; k + 1 < ends.size(); ++k) {
    const End &a = ends[k], &b = ends[k + 1];
    if (a.x != b.x || a.piece == b.piece || a.start == b.start)
      continue;  // not the end of one and the start of another
    for (const auto& [short_end, long_end] : {std::pair{a, b}, std::pair{b, a}}) {
      const std::size_t p = short_end.piece, q = long_end.piece;
      // Cut inside its segment at its other end, and short against the piece it meets.
      const bool cut = short_end.start ? s[p].t1 < 1.0 : s[p].t0 > 0.0;
      if (!cut || !(length(p) < fraction * length(q))) continue;
      const double c = direction(p).dot(direction(q));
      if (c < cos_turn)
        out.push_back(
            {s[p], short_end.x, length(p), std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / std::numbers::pi});
    }
  }
  return out;
}

BoundarySelection<2> select_part(const Domain& domain, const std::string& name) {
  const auto& names = domain.part_names();
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end())
    throw InputError(names.empty() ? fmt::format("the domain has no named boundary parts (no part '{}'): select by "
                                                 "ring, edges or region",
                                                 name)
                                   : fmt::format("the domain has no boundary part '{}'; its parts are: {}", name,
                                                 fmt::join(names, ", ")));
  const int part = static_cast<int>(it - names.begin());
  for (const Crack& c : domain.cracks())
    if (c.interface() && c.name == name)
      throw InputError(
          fmt::format("'{}' is an interface between two regions: its faces are tied to each other "
                      "and take no boundary condition",
                      name));
  return whole_segments(domain, [&](const BoundarySegment& s) { return s.part == part; });
}

BoundarySelection<3> select_part(const Solid& solid, const std::string& name) {
  const auto& names = solid.parts();
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end())
    throw InputError(
        fmt::format("the solid has no surface part '{}'; its parts are: {}", name, fmt::join(names, ", ")));
  const int part = static_cast<int>(it - names.begin());
  BoundarySelection<3> out;
  const auto& surface = solid.surface();
  for (std::size_t t = 0; t < surface.size(); ++t)
    if (surface[t].part == part) out.push_back({static_cast<Index>(t), std::nullopt});
  return out;
}

BoundarySelection<3> select_box(const Solid& solid, const AlignedBox<3>& box) {
  BoundarySelection<3> out;
  const auto& surface = solid.surface();
  for (std::size_t t = 0; t < surface.size(); ++t) {
    const BoundaryPiece<3> piece{static_cast<Index>(t), box};
    if (polygon_area(piece_polygon(solid, piece)) > 0.0) out.push_back(piece);
  }
  return out;
}

double selection_area(const Solid& solid, const BoundarySelection<3>& s) {
  double area = 0.0;
  for (const BoundaryPiece<3>& p : s) area += polygon_area(piece_polygon(solid, p));
  return area;
}

double overlap_area(const Solid& solid, const BoundarySelection<3>& a, const BoundarySelection<3>& b) {
  double area = 0.0;
  auto first = b.begin();  // both in triangle order
  for (const BoundaryPiece<3>& p : a) {
    while (first != b.end() && first->triangle < p.triangle) ++first;
    for (auto q = first; q != b.end() && q->triangle == p.triangle; ++q) {
      std::vector<Point<3>> shared = piece_polygon(solid, p);
      if (q->clip) shared = clip_to_box(ConvexPolygon(shared.begin(), shared.end()), *q->clip);
      area += polygon_area(shared);
    }
  }
  return area;
}

std::vector<Point<3>> piece_polygon(const Solid& solid, const BoundaryPiece<3>& piece) {
  const auto& v = solid.surface()[static_cast<std::size_t>(piece.triangle)].vertices;
  ConvexPolygon p(v.begin(), v.end());
  return piece.clip ? clip_to_box(std::move(p), *piece.clip) : p;
}

BoundarySelection<2> select_ring(const Domain& domain, int ring) {
  if (ring < 0 || ring >= ring_count(domain))
    throw InputError(fmt::format("the domain has no ring {} (rings 0 to {}: 0 the outer boundary, then the holes)", ring,
                                 ring_count(domain) - 1));
  return whole_segments(domain, [&](const BoundarySegment& s) { return s.ring == ring; });
}

BoundarySelection<2> select_edges(const Domain& domain, int ring, const std::vector<int>& edges) {
  (void)select_ring(domain, ring);  // checks the ring
  const int n = static_cast<int>(domain.rings()[ring].size());
  for (int e : edges)
    if (e < 0 || e >= n) throw InputError(fmt::format("ring {} has no edge {} (edges 0 to {})", ring, e, n - 1));
  return whole_segments(domain, [&](const BoundarySegment& s) {
    return s.ring == ring && std::find(edges.begin(), edges.end(), s.edge) != edges.end();
  });
}

std::optional<std::array<double, 2>> segment_in_box(const Vec2& a, const Vec2& b, const Box& box) {
  // Liang–Barsky: a + t d inside the box for t in [t0, t1].
  const Vec2 d = b - a;
  double t0 = 0.0, t1 = 1.0;
  for (int c = 0; c < 2; ++c) {
    if (d[c] == 0.0) {
      if (a[c] < box.lo[c] || a[c] > box.hi[c]) return std::nullopt;
      continue;
    }
    double lo = (box.lo[c] - a[c]) / d[c], hi = (box.hi[c] - a[c]) / d[c];
    if (lo > hi) std::swap(lo, hi);
    t0 = std::max(t0, lo);
    t1 = std::min(t1, hi);
    if (!(t1 > t0)) return std::nullopt;
  }
  return std::array<double, 2>{t0, t1};
}

BoundarySelection<2> select_box(const Domain& domain, const Box& box) {
  BoundarySelection<2> out;
  const auto& segments = domain.boundary();
  for (std::size_t s = 0; s < segments.size(); ++s) {
    // The faces of an interface are tied to each other, not a boundary a condition holds on.
    if (segments[s].crack >= 0 && domain.cracks()[segments[s].crack].interface()) continue;
    if (const auto t = segment_in_box(segments[s].a, segments[s].b, box))
      out.push_back({static_cast<Index>(s), (*t)[0], (*t)[1]});
  }
  return out;
}

double overlap_length(const Domain& domain, const BoundarySelection<2>& a, const BoundarySelection<2>& b) {
  double length = 0.0;
  for (const BoundaryPiece<2>& p : a)
    for (const BoundaryPiece<2>& q : b)
      if (p.segment == q.segment)
        length += std::max(0.0, std::min(p.t1, q.t1) - std::max(p.t0, q.t0)) * domain.boundary()[p.segment].length;
  return length;
}

}  // namespace mfree
