#include "mfree/geometry/domain_triangulation.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_face_base_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_data_structure_2.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <deque>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <utility>
#include <vector>

#include "mfree/core/error.hpp"
#include "mfree/geometry/crack_faces.hpp"

namespace mfree {

namespace {

/// Index of a vertex in Triangulation::points; -1 until one is given.
struct PointId {
  Index index = -1;
};

/// How many constrained edges separate a face from the unbounded region; -1 until known.
/// Odd levels are inside the domain: the outer ring is crossed once, a hole's ring twice.
struct NestingLevel {
  int level = -1;
};

// Exact predicates on the double coordinates (Epick) make the triangulation valid however
// close points come. The domain's rings are simple and do not touch (domain.hpp), and every
// point is in the closed domain, so constraints meet only at their end vertices or where a
// point lies on one: CGAL never has to construct a crossing, and the tag makes it refuse to.
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<PointId, Kernel>;
using FaceBase = CGAL::Triangulation_face_base_with_info_2<
    NestingLevel, Kernel, CGAL::Constrained_triangulation_face_base_2<Kernel>>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<
    Kernel, Tds, CGAL::No_constraint_intersection_requiring_constructions_tag>;
using CgalPoint = Kernel::Point_2;

/// Relative to the bounding-box diagonal: how far outside the boundary a point may lie.
constexpr double outside_tolerance = 1e-9;

/// The point of the segment a -> b nearest to x.
Vec2 nearest_on_segment(const Vec2& x, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double t = std::clamp((x - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  // t = 0 and t = 1 give the end vertices exactly.
  return t == 1.0 ? b : a + t * d;
}

/// A point of the closed domain near x, which lies just outside it: the nearest boundary
/// point, stepped inwards by a few ulps when rounding left it outside. Returns false when x
/// is farther than `tolerance` from the boundary.
bool snap_into(const Domain& domain, const Vec2& x, double tolerance, Vec2& snapped) {
  const std::vector<BoundarySegment>& segments = domain.boundary();
  std::size_t nearest = 0;
  Vec2 foot = nearest_on_segment(x, segments[0].a, segments[0].b);
  for (std::size_t s = 1; s < segments.size(); ++s) {
    const Vec2 q = nearest_on_segment(x, segments[s].a, segments[s].b);
    if ((q - x).norm() < (foot - x).norm()) {
      nearest = s;
      foot = q;
    }
  }
  if ((foot - x).norm() > tolerance) return false;
  double step = std::numeric_limits<double>::epsilon() * std::max(1.0, foot.cwiseAbs().maxCoeff());
  Vec2 q = foot;
  while (!domain.contains(q)) {
    if (step > tolerance) return false;
    q = foot - step * segments[nearest].normal;
    step *= 2.0;
  }
  snapped = q;
  return true;
}

/// A vertex of a crack (not a tip) that the triangulation added, and its neighbours along
/// the crack (none beyond a mouth).
struct FaceSplit {
  Index index;
  Vec2 at;
  std::optional<Vec2> previous, next;
};

/// Angle of d counter-clockwise from `from`, in [0, 2 pi).
double angle_from(const Vec2& from, const Vec2& d) {
  const double a = std::atan2(from.x() * d.y() - from.y() * d.x(), from.dot(d));
  return a < 0.0 ? a + 2.0 * std::numbers::pi : a;
}

/// A crack's vertex lies on both faces: each face's triangles get a copy of their own, sampled
/// a little into the face (Triangulation::samples), so that a warped plot opens there too. The
/// left face's copy keeps the vertex's index, the right face's is appended.
void split_crack_vertices(const Domain& domain, const std::vector<FaceSplit>& splits, Triangulation& out) {
  out.samples = out.points;
  std::map<Index, std::size_t> split_of;
  std::vector<Index> right(splits.size());
  for (std::size_t k = 0; k < splits.size(); ++k) {
    const FaceSplit& f = splits[k];
    split_of.emplace(f.index, k);
    // The face copies of the clouds (crack_faces.hpp), with the shorter crack segment at the
    // vertex as the spacing: the left copy first.
    double shortest = std::numeric_limits<double>::infinity();
    for (const std::optional<Vec2>& n : {f.previous, f.next})
      if (n) shortest = std::min(shortest, (*n - f.at).norm());
    const std::vector<Vec2> copies = split_on_cracks(domain, {f.at}, shortest);
    if (copies.size() != 2)
      throw Error(
          fmt::format("triangulate_domain: the crack vertex ({}, {}) was not split", f.at.x(), f.at.y()));
    out.samples[f.index] = copies[0];
    right[k] = static_cast<Index>(out.points.size());
    out.points.push_back(f.at);
    out.samples.push_back(copies[1]);
  }
  if (splits.empty()) return;
  for (std::array<Index, 3>& t : out.triangles) {
    const Vec2 centroid = (out.points[t[0]] + out.points[t[1]] + out.points[t[2]]) / 3.0;
    for (Index& i : t) {
      const auto found = split_of.find(i);
      if (found == split_of.end()) continue;
      const FaceSplit& f = splits[found->second];
      const Vec2 d = centroid - f.at;
      // Left of the crack: counter-clockwise from the way to the next vertex to the way back.
      bool left;
      if (f.previous && f.next)
        left = angle_from(*f.next - f.at, d) < angle_from(*f.next - f.at, *f.previous - f.at);
      else
        left = f.next ? orientation(f.at, *f.next, centroid) > 0.0
                      : orientation(*f.previous, f.at, centroid) > 0.0;
      if (!left) i = right[found->second];
    }
  }
}

/// Sets every face's nesting level by flooding from the unbounded region: faces reached
/// without crossing a constraint share a level, crossing one adds 1 (a passable one, a
/// crack's, adds nothing: the material is on both of its sides). Breadth-first over
/// levels, so each region is reached first from the region enclosing it.
template <class Passable>
void mark_nesting_levels(Cdt& cdt, Passable&& passable) {
  std::deque<Cdt::Edge> border;  // constrained edges whose far side may be unmarked
  std::vector<Cdt::Face_handle> stack;
  const auto flood = [&](Cdt::Face_handle start, int level) {
    if (start->info().level != -1) return;
    start->info().level = level;
    stack.push_back(start);
    while (!stack.empty()) {
      const Cdt::Face_handle f = stack.back();
      stack.pop_back();
      for (int i = 0; i < 3; ++i) {
        const Cdt::Face_handle n = f->neighbor(i);
        if (n->info().level != -1) continue;
        if (cdt.is_constrained(Cdt::Edge(f, i)) && !passable(Cdt::Edge(f, i))) {
          border.emplace_back(f, i);
        } else {
          n->info().level = level;
          stack.push_back(n);
        }
      }
    }
  };
  flood(cdt.infinite_face(), 0);
  while (!border.empty()) {
    const Cdt::Edge e = border.front();
    border.pop_front();
    flood(e.first->neighbor(e.second), e.first->info().level + 1);
  }
}

}  // namespace

std::optional<std::vector<std::array<Vec2, 3>>> triangulate_rings(const std::vector<Ring>& rings) {
  Cdt cdt;
  try {
    for (const Ring& ring : rings) {
      std::vector<Cdt::Vertex_handle> v;
      for (const Vec2& x : ring) v.push_back(cdt.insert(CgalPoint(x.x(), x.y())));
      for (std::size_t i = 0; i < v.size(); ++i)
        if (v[i] != v[(i + 1) % v.size()]) cdt.insert_constraint(v[i], v[(i + 1) % v.size()]);
    }
  } catch (const Cdt::Intersection_of_constraints_exception&) {
    return std::nullopt;
  }
  mark_nesting_levels(cdt, [](const Cdt::Edge&) { return false; });
  std::vector<std::array<Vec2, 3>> out;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    if (f->info().level % 2 == 0) continue;
    std::array<Vec2, 3> t;
    for (int k = 0; k < 3; ++k) t[k] = Vec2(f->vertex(k)->point().x(), f->vertex(k)->point().y());
    out.push_back(t);
  }
  return out;
}

Triangulation triangulate_domain(const Domain& domain, const std::vector<Vec2>& points) {
  // The rings' edges; crack faces (after them) bound no area.
  std::vector<BoundarySegment> segments = domain.boundary();
  segments.erase(
      std::find_if(segments.begin(), segments.end(), [](const BoundarySegment& s) { return s.ring < 0; }),
      segments.end());
  const double tolerance = outside_tolerance * domain.bounding_box().size().norm();

  Triangulation out;
  out.points = points;
  out.input_points = static_cast<Index>(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec2& x = points[i];
    if (!x.allFinite()) {
      throw InputError(fmt::format("triangulate_domain: point {} is not finite (({}, {}))", i,
                                   x.x(), x.y()));
    }
    if (!domain.contains(x) && !snap_into(domain, x, tolerance, out.points[i])) {
      throw InputError(fmt::format(
          "triangulate_domain: point {} at ({}, {}) lies outside the domain; only points "
          "inside it or within {} of its boundary can be triangulated",
          i, x.x(), x.y(), tolerance));
    }
  }

  Cdt cdt;
  {
    std::vector<std::pair<CgalPoint, PointId>> given;
    given.reserve(out.points.size());
    for (std::size_t i = 0; i < out.points.size(); ++i) {
      const Vec2& x = out.points[i];
      given.emplace_back(CgalPoint(x.x(), x.y()), PointId{static_cast<Index>(i)});
    }
    cdt.insert(given.begin(), given.end());  // spatially sorted, deterministic
  }

  // Boundary vertices in ring order; one that coincides with a given point keeps its index.
  std::vector<Cdt::Vertex_handle> segment_start(segments.size());
  Cdt::Face_handle hint;
  for (std::size_t s = 0; s < segments.size(); ++s) {
    const Vec2& a = segments[s].a;
    const Cdt::Vertex_handle v = cdt.insert(CgalPoint(a.x(), a.y()), hint);
    if (v->info().index < 0) {
      v->info().index = static_cast<Index>(out.points.size());
      out.points.push_back(a);
    }
    segment_start[s] = v;
    hint = v->face();
  }
  // Segment s runs to the start of the next segment of its ring (the ring's first one for
  // its last segment). CGAL splits a constraint at the points lying on it.
  std::size_t ring_start = 0;
  for (std::size_t s = 0; s < segments.size(); ++s) {
    if (segments[s].ring != segments[ring_start].ring) ring_start = s;
    const bool last_of_ring = s + 1 == segments.size() || segments[s + 1].ring != segments[s].ring;
    cdt.insert_constraint(segment_start[s], segment_start[last_of_ring ? ring_start : s + 1]);
  }

  // Cracks: constraints through the material, so that no triangle spans the two faces (the
  // points on them are split, one copy per face: crack_faces.hpp) and the opening shows.
  // Inserting the constraints above may have removed the hint's face: start without one.
  hint = Cdt::Face_handle();
  std::vector<FaceSplit> splits;  // the crack vertices this triangulation added, but tips
  for (const Crack& c : domain.cracks()) {
    Cdt::Vertex_handle previous;
    const std::size_t n = c.points.size();
    const bool closed = c.closed();
    for (std::size_t i = 0; i < n; ++i) {
      const Vec2& a = c.points[i];
      const Cdt::Vertex_handle v = cdt.insert(CgalPoint(a.x(), a.y()), hint);
      if (v->info().index < 0) {
        v->info().index = static_cast<Index>(out.points.size());
        out.points.push_back(a);
        const bool first = i == 0 && !closed, last = i + 1 == n && !closed;
        if (!(first && c.tip[0]) && !(last && c.tip[1]))
          splits.push_back(
              {v->info().index, a,
               first ? std::nullopt : std::optional<Vec2>(c.points[closed && i == 0 ? n - 2 : i - 1]),
               last ? std::nullopt : std::optional<Vec2>(c.points[closed && i + 1 == n ? 1 : i + 1])});
      }
      if (previous != Cdt::Vertex_handle()) cdt.insert_constraint(previous, v);
      previous = v;
      hint = v->face();
    }
  }
  const auto on_crack = [&](const Cdt::Edge& e) {
    const CgalPoint& p = e.first->vertex(Cdt::cw(e.second))->point();
    const CgalPoint& q = e.first->vertex(Cdt::ccw(e.second))->point();
    for (const Crack& c : domain.cracks())
      for (std::size_t i = 0; i + 1 < c.points.size(); ++i) {
        const CgalPoint a(c.points[i].x(), c.points[i].y()), b(c.points[i + 1].x(), c.points[i + 1].y());
        if (CGAL::collinear(a, b, p) && CGAL::collinear(a, b, q) &&
            CGAL::collinear_are_ordered_along_line(a, p, b) &&
            CGAL::collinear_are_ordered_along_line(a, q, b))
          return true;
      }
    return false;
  };
  mark_nesting_levels(cdt, on_crack);
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    if (f->info().level % 2 == 1) {
      // CGAL's faces are counter-clockwise.
      out.triangles.push_back(
          {f->vertex(0)->info().index, f->vertex(1)->info().index, f->vertex(2)->info().index});
    }
  }
  split_crack_vertices(domain, splits, out);
  return out;
}

}  // namespace mfree
