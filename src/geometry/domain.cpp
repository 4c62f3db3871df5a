#include "mfree/geometry/domain.hpp"

#include <CGAL/Boolean_set_operations_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2.h>
#include <CGAL/Polygon_with_holes_2.h>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <tuple>
#include <utility>

#include "mfree/core/error.hpp"
#include "mfree/geometry/gmsh_domain.hpp"
#include "mfree/geometry/polygon_integrals.hpp"
#include "mfree/geometry/segment_grid.hpp"

namespace mfree {

namespace {

// Inside tests use exact predicates on double coordinates (Epick): exact answers, no
// allocation. Boolean clipping constructs new points (edge crossings), so it runs on the
// exact-constructions kernel (Epeck) and the results are rounded back to double.
using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using Epeck = CGAL::Exact_predicates_exact_constructions_kernel;
using FastPolygon = CGAL::Polygon_2<Epick>;
using ExactPolygon = CGAL::Polygon_2<Epeck>;
using ExactPolygonWithHoles = CGAL::Polygon_with_holes_2<Epeck>;

std::string ring_name(std::size_t k) {
  return k == 0 ? std::string("the outer ring") : fmt::format("hole {}", k);
}

/// What a WKT text holds: polygons (one, or the regions of the domain) and the line strings
/// beside them (cracks).
struct WktGeometry {
  std::vector<std::vector<Ring>> polygons;
  std::vector<std::vector<Vec2>> lines;
};

/// Strict reader of WKT: POLYGON ((x y, x y, ...), (x y, ...), ...), a MULTIPOLYGON, or a
/// GEOMETRYCOLLECTION of POLYGONs (or MULTIPOLYGONs) and LINESTRINGs or MULTILINESTRINGs.
/// Keywords are case-insensitive; anything else (Z/M coordinates, EMPTY, other geometries,
/// trailing text) is an error reported with its line and column.
class WktReader {
 public:
  WktReader(std::string_view text, const std::string& source) : text_(text), source_(source) {}

  WktGeometry geometry() {
    WktGeometry g;
    skip_space();
    if (at_keyword("GEOMETRYCOLLECTION")) {
      pos_ += std::string_view("GEOMETRYCOLLECTION").size();
      expect('(');
      do {
        skip_space();
        if (at_keyword("POLYGON")) {
          g.polygons.push_back(polygon());
        } else if (at_keyword("MULTIPOLYGON")) {
          multipolygon(g.polygons);
        } else if (at_keyword("LINESTRING")) {
          pos_ += std::string_view("LINESTRING").size();
          g.lines.push_back(ring());
        } else if (at_keyword("MULTILINESTRING")) {
          pos_ += std::string_view("MULTILINESTRING").size();
          expect('(');
          do {
            g.lines.push_back(ring());
          } while (accept(','));
          expect(')');
        } else {
          fail("expected POLYGON, MULTIPOLYGON, LINESTRING or MULTILINESTRING in the collection");
        }
      } while (accept(','));
      expect(')');
      if (g.polygons.empty()) fail("the collection has no POLYGON");
    } else if (at_keyword("MULTIPOLYGON")) {
      multipolygon(g.polygons);
    } else {
      g.polygons.push_back(polygon());
    }
    skip_space();
    if (pos_ != text_.size()) fail("unexpected text after the geometry");
    return g;
  }

 private:
  std::vector<Ring> polygon() {
    skip_space();
    expect_keyword("POLYGON");
    return polygon_body();
  }

  void multipolygon(std::vector<std::vector<Ring>>& out) {
    skip_space();
    expect_keyword("MULTIPOLYGON");
    skip_space();
    if (at_keyword("EMPTY")) fail("MULTIPOLYGON EMPTY has no area");
    expect('(');
    do {
      out.push_back(polygon_body());
    } while (accept(','));
    expect(')');
  }

  std::vector<Ring> polygon_body() {
    skip_space();
    if (at_keyword("EMPTY")) fail("POLYGON EMPTY has no area");
    expect('(');
    std::vector<Ring> rings;
    do {
      rings.push_back(ring());
    } while (accept(','));
    expect(')');
    return rings;
  }

  Ring ring() {
    expect('(');
    Ring r;
    do {
      const double x = number();
      const double y = number();
      r.emplace_back(x, y);
    } while (accept(','));
    expect(')');
    return r;
  }

  double number() {
    skip_space();
    const char* first = text_.data() + pos_;
    const char* last = text_.data() + text_.size();
    double value = 0.0;
    const auto [end, ec] = std::from_chars(first, last, value);
    if (ec != std::errc() || end == first) fail("expected a number");
    if (!std::isfinite(value)) fail("coordinates must be finite numbers");
    pos_ += static_cast<std::size_t>(end - first);
    return value;
  }

  void skip_space() {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
  }

  bool accept(char c) {
    skip_space();
    if (pos_ < text_.size() && text_[pos_] == c) {
      ++pos_;
      return true;
    }
    return false;
  }

  void expect(char c) {
    if (!accept(c)) fail(fmt::format("expected '{}'", c));
  }

  bool at_keyword(std::string_view word) const {
    if (text_.size() - pos_ < word.size()) return false;
    for (std::size_t i = 0; i < word.size(); ++i) {
      if (std::toupper(static_cast<unsigned char>(text_[pos_ + i])) != word[i]) return false;
    }
    const std::size_t after = pos_ + word.size();
    return after == text_.size() || !std::isalnum(static_cast<unsigned char>(text_[after]));
  }

  void expect_keyword(std::string_view word) {
    if (!at_keyword(word))
      fail(
          fmt::format("expected {} (mfree reads a POLYGON or the regions of a MULTIPOLYGON, alone or in a "
                      "GEOMETRYCOLLECTION with LINESTRING cracks)",
                      word));
    pos_ += word.size();
  }

  [[noreturn]] void fail(const std::string& what) const {
    std::size_t line = 1, column = 1;
    for (std::size_t i = 0; i < pos_ && i < text_.size(); ++i) {
      if (text_[i] == '\n') {
        ++line;
        column = 1;
      } else {
        ++column;
      }
    }
    throw InputError(fmt::format("{}:{}:{}: malformed WKT: {}", source_, line, column, what));
  }

  std::string_view text_;
  const std::string& source_;
  std::size_t pos_ = 0;
};

Epick::Point_2 fast_point(const Vec2& x) { return {x.x(), x.y()}; }
Epeck::Point_2 exact_point(const Vec2& x) { return {x.x(), x.y()}; }

FastPolygon fast_polygon(const Ring& ring) {
  FastPolygon p;
  for (const Vec2& x : ring) p.push_back(fast_point(x));
  return p;
}

ExactPolygon exact_polygon(const Ring& ring) {
  ExactPolygon p;
  for (const Vec2& x : ring) p.push_back(exact_point(x));
  return p;
}

Ring to_ring(const ExactPolygon& p) {
  Ring r;
  r.reserve(p.size());
  for (auto v = p.vertices_begin(); v != p.vertices_end(); ++v) {
    r.emplace_back(CGAL::to_double(v->x()), CGAL::to_double(v->y()));
  }
  return r;
}

/// Whether the interiors of two boxes overlap (touching along an edge does not count).
bool interiors_overlap(const Box& a, const Box& b) {
  return a.lo.x() < b.hi.x() && b.lo.x() < a.hi.x() && a.lo.y() < b.hi.y() && b.lo.y() < a.hi.y();
}

/// Whether every vertex lies on one straight line (exact predicate), i.e. zero area.
bool all_collinear(const Ring& r) {
  const auto other = std::find_if(r.begin(), r.end(), [&](const Vec2& x) { return x != r[0]; });
  if (other == r.end()) return true;
  return std::all_of(r.begin(), r.end(), [&](const Vec2& x) {
    return CGAL::collinear(fast_point(r[0]), fast_point(*other), fast_point(x));
  });
}

/// Validates raw rings from the input and orients them: outer CCW, holes CW. `reversed`
/// gets, per ring, whether it was reversed (edge numbers refer to the rings as given).
/// `parts`, when given, holds a part per edge of every ring as given. `source` names the
/// input in error messages.
std::vector<Ring> normalised_rings(std::vector<Ring> rings, const std::string& source, std::vector<bool>& reversed,
                                   std::vector<std::vector<int>>* parts = nullptr) {
  reversed.assign(rings.size(), false);
  for (std::size_t k = 0; k < rings.size(); ++k) {
    Ring& r = rings[k];
    if (r.size() > 1 && r.front() == r.back()) {
      r.pop_back();
      if (parts && (*parts)[k].size() == r.size() + 1) (*parts)[k].pop_back();  // the degenerate closing edge
    }
    if (parts && (*parts)[k].size() != r.size())
      throw InputError(fmt::format("{}: {} has {} edges but {} edge parts", source, ring_name(k), r.size(), (*parts)[k].size()));
    if (r.size() < 3) {
      throw InputError(fmt::format("{}: {} has {} distinct vertices; a ring needs at least 3",
                                   source, ring_name(k), r.size()));
    }
    if (all_collinear(r)) {
      throw InputError(fmt::format("{}: {} has zero area", source, ring_name(k)));
    }
    const FastPolygon p = fast_polygon(r);
    if (!p.is_simple()) {
      throw InputError(fmt::format(
          "{}: {} is not simple (it crosses itself or repeats a vertex)", source, ring_name(k)));
    }
    const bool ccw = p.orientation() == CGAL::COUNTERCLOCKWISE;
    if (ccw != (k == 0)) {
      std::reverse(r.begin(), r.end());
      reversed[k] = true;
    }
  }

  // Holes must lie strictly inside the outer ring and outside each other: no edge of one
  // ring may meet an edge of another, and with that settled one vertex per ring decides
  // nesting.
  std::vector<FastPolygon> polys;
  std::vector<Box> boxes;
  for (const Ring& r : rings) {
    polys.push_back(fast_polygon(r));
    boxes.push_back(ring_bounding_box(r));
  }
  for (std::size_t i = 0; i < rings.size(); ++i) {
    for (std::size_t j = i + 1; j < rings.size(); ++j) {
      const Box& a = boxes[i];
      const Box& b = boxes[j];
      if (a.hi.x() < b.lo.x() || b.hi.x() < a.lo.x() || a.hi.y() < b.lo.y() || b.hi.y() < a.lo.y())
        continue;
      for (auto e = polys[i].edges_begin(); e != polys[i].edges_end(); ++e) {
        for (auto f = polys[j].edges_begin(); f != polys[j].edges_end(); ++f) {
          if (CGAL::do_intersect(*e, *f)) {
            throw InputError(fmt::format("{}: {} and {} touch or cross", source, ring_name(i),
                                         ring_name(j)));
          }
        }
      }
    }
  }
  for (std::size_t k = 1; k < rings.size(); ++k) {
    if (polys[0].bounded_side(polys[k].vertex(0)) != CGAL::ON_BOUNDED_SIDE) {
      throw InputError(fmt::format("{}: {} lies outside the outer ring", source, ring_name(k)));
    }
    for (std::size_t m = 1; m < rings.size(); ++m) {
      if (m != k && polys[m].bounded_side(polys[k].vertex(0)) == CGAL::ON_BOUNDED_SIDE) {
        throw InputError(fmt::format("{}: {} lies inside {}", source, ring_name(k), ring_name(m)));
      }
    }
  }
  return rings;
}

}  // namespace

struct Domain::Impl {
  std::vector<Ring> rings;
  std::vector<FastPolygon> fast_rings;  // rings for the inside test
  std::vector<Box> ring_boxes;
  std::vector<BoundarySegment> segments;
  SegmentGrid grid;
  Box box;
  double area = 0.0;
  Vec2 first_moment = Vec2::Zero();

  std::vector<std::string> part_names;
  std::vector<Crack> cracks;
  std::vector<Region> regions;
  std::vector<std::vector<FastPolygon>> region_polygons;  // per region, its rings
  std::vector<Box> region_boxes;

  explicit Impl(std::vector<Ring> oriented, const std::vector<bool>& reversed,
                const std::vector<std::vector<int>>& parts = {}, std::vector<std::string> names = {})
      : rings(std::move(oriented)), segments(make_segments(rings, reversed, parts)), grid(segments),
        part_names(std::move(names)) {
    for (const Ring& r : rings) {
      fast_rings.push_back(fast_polygon(r));
      ring_boxes.push_back(ring_bounding_box(r));
      // Holes are clockwise: their signed integrals subtract (polygon_integrals.hpp).
      area += ring_area(r);
      first_moment += ring_first_moment(r);
    }
    box = ring_boxes[0];
  }

  static std::vector<BoundarySegment> make_segments(const std::vector<Ring>& rings, const std::vector<bool>& reversed,
                                                    const std::vector<std::vector<int>>& parts) {
    std::vector<BoundarySegment> out;
    for (std::size_t k = 0; k < rings.size(); ++k) {
      const Ring& r = rings[k];
      for (std::size_t i = 0; i < r.size(); ++i) {
        const Vec2& a = r[i];
        const Vec2& b = r[(i + 1) % r.size()];
        const double length = (b - a).norm();
        const Vec2 t = (b - a) / length;
        // The domain lies to the left of a -> b, so the outward normal is t turned clockwise.
        // Edge i of a reversed ring runs backwards along edge n - 2 - i (mod n) as given.
        const std::size_t n = r.size(), given = reversed[k] ? (2 * n - 2 - i) % n : i;
        const int part = parts.empty() ? -1 : parts[k][given];
        out.push_back(BoundarySegment{a, b, Vec2(t.y(), -t.x()), length, static_cast<int>(k), static_cast<int>(given), part});
      }
    }
    return out;
  }
};

namespace {

using FastSegment = Epick::Segment_2;

std::string crack_point(const std::string& name, std::size_t i, const Vec2& x) {
  return fmt::format("crack '{}', point {} ({}, {})", name, i + 1, x.x(), x.y());
}

/// Whether x lies on the boundary of one of the rings.
bool on_boundary(const std::vector<FastPolygon>& rings, const Vec2& x) {
  return std::any_of(rings.begin(), rings.end(), [&](const FastPolygon& r) {
    return r.bounded_side(fast_point(x)) == CGAL::ON_BOUNDARY;
  });
}

/// Whether segments s and t share more than the one point `shared` (an end of both).
bool overlap_beyond(const FastSegment& s, const FastSegment& t, const Epick::Point_2& shared) {
  const Epick::Point_2 other = s.source() == shared ? s.target() : s.source();
  const Epick::Point_2 far = t.source() == shared ? t.target() : t.source();
  return CGAL::collinear(shared, other, far) && CGAL::angle(other, shared, far) == CGAL::ACUTE;
}

}  // namespace

Domain Domain::with_cracks(std::vector<std::vector<Vec2>> lines, std::vector<std::string> names,
                           const std::string& source, const std::vector<std::pair<int, int>>& sides) const {
  if (names.size() != lines.size() || (!sides.empty() && sides.size() != lines.size()))
    throw Error(fmt::format("{}: {} cracks but {} names and {} sides", source, lines.size(), names.size(),
                            sides.size()));
  auto impl = std::make_unique<Impl>(*impl_);
  // Every segment of every crack, bucketed, for the test that no two meet.
  std::vector<BoundarySegment> pieces;
  for (std::size_t c = 0; c < lines.size(); ++c) {
    if (lines[c].size() < 2)
      throw InputError(fmt::format("{}: crack '{}' has {} point(s); a crack needs at least 2", source,
                                   names[c], lines[c].size()));
    for (std::size_t i = 0; i < lines[c].size(); ++i)
      if (!lines[c][i].allFinite())
        throw InputError(fmt::format("{}: {} is not finite", source, crack_point(names[c], i, lines[c][i])));
    for (std::size_t i = 0; i + 1 < lines[c].size(); ++i)
      pieces.push_back(BoundarySegment{lines[c][i], lines[c][i + 1], Vec2::Zero(), 0.0, -1,
                                       static_cast<int>(i), -1, static_cast<int>(c)});
  }
  const SegmentGrid pieces_grid(pieces);
  std::vector<FastSegment> all;    // every crack segment so far
  std::vector<std::size_t> owner;  // its crack
  for (std::size_t c = 0; c < lines.size(); ++c) {
    std::vector<Vec2>& line = lines[c];
    const std::string& name = names[c];
    const bool taken =
        std::find(impl->part_names.begin(), impl->part_names.end(), name) != impl->part_names.end();
    if (name.empty() || taken)
      throw InputError(
          fmt::format("{}: crack name '{}' is {}", source, name, taken ? "already a part name" : "empty"));
    Crack crack{line, name, {false, false}};
    if (!sides.empty()) std::tie(crack.left, crack.right) = sides[c];
    const bool closed = crack.closed();
    if (closed && !crack.interface())
      throw InputError(fmt::format(
          "{}: crack '{}' closes on itself at ({}, {}): it would cut its inside loose; a hole is a "
          "ring of the polygon, an inclusion a region of its own",
          source, name, line.front().x(), line.front().y()));
    for (std::size_t i = 0; i < line.size(); ++i) {
      const Vec2& x = line[i];
      if (!contains(x))
        throw InputError(fmt::format("{}: {} lies outside the domain", source, crack_point(name, i, x)));
      const bool end = !closed && (i == 0 || i + 1 == line.size());
      const bool boundary = on_boundary(impl->fast_rings, x);
      if (boundary && !end)
        throw InputError(fmt::format("{}: {} lies on the boundary; only an end of a crack may (its mouth)",
                                     source, crack_point(name, i, x)));
      if (end) crack.tip[i == 0 ? 0 : 1] = !boundary;
      if (i > 0 && x == line[i - 1])
        throw InputError(fmt::format("{}: {} repeats the point before it", source, crack_point(name, i, x)));
    }
    for (std::size_t i = 0; i + 1 < line.size(); ++i) {
      const FastSegment seg(fast_point(line[i]), fast_point(line[i + 1]));
      // Against the boundary: a crack meets it at a mouth only.
      impl->grid.for_each_meeting(
          Box{line[i].cwiseMin(line[i + 1]), line[i].cwiseMax(line[i + 1])}, [&](int k) {
            const BoundarySegment& e = impl->segments[k];
            const FastSegment edge(fast_point(e.a), fast_point(e.b));
            if (!CGAL::do_intersect(seg, edge)) return;
            if (e.ring < 0)  // a crack or interface the domain has already
              throw InputError(fmt::format(
                  "{}: crack '{}', segment {} meets {} '{}'; cracks do not cross or touch", source, name,
                  i + 1, impl->cracks[e.crack].interface() ? "the interface" : "crack",
                  impl->cracks[e.crack].name));
            // Segments not on one line meet at one point: allowed when it is a mouth.
            const bool mouth_here = (i == 0 && !crack.tip[0] && edge.has_on(seg.source())) ||
                                    (i + 2 == line.size() && !crack.tip[1] && edge.has_on(seg.target()));
            // On one line with the edge: allowed when they share the mouth only (the boundary
            // runs straight on past an interface's end, as beside a lap joint).
            const Epick::Point_2 mouth = edge.has_on(seg.source()) ? seg.source() : seg.target();
            const bool along =
                CGAL::collinear(edge.source(), edge.target(), seg.source()) &&
                CGAL::collinear(edge.source(), edge.target(), seg.target()) &&
                (!(edge.source() == mouth || edge.target() == mouth) || overlap_beyond(edge, seg, mouth));
            if (!mouth_here || along)
              throw InputError(fmt::format(
                  "{}: crack '{}', segment {} (from ({}, {}) to ({}, {})) meets the boundary of the "
                  "domain at {} ({} edge {}); a crack lies inside the domain and only its ends may "
                  "touch the boundary",
                  source, name, i + 1, line[i].x(), line[i].y(), line[i + 1].x(), line[i + 1].y(),
                  mouth_here ? "more than its mouth" : "a point other than its ends",
                  ring_name(static_cast<std::size_t>(e.ring)), e.edge + 1));
          });
      // Against itself and the cracks before it: no crossing, touching or doubling back.
      const int here = static_cast<int>(all.size());
      pieces_grid.for_each_meeting(
          Box{line[i].cwiseMin(line[i + 1]), line[i].cwiseMax(line[i + 1])}, [&](int k) {
            if (k >= here) return;
            // The segment before, and for the last of a closed line its first, share an end.
            const bool previous = owner[k] == c && k + 1 == here;
            const bool closing =
                closed && i + 2 == line.size() && owner[k] == c && k == here - static_cast<int>(i);
            if (closing) {
              if (overlap_beyond(all[k], seg, seg.target()))
                throw InputError(
                    fmt::format("{}: crack '{}', segment {} folds back onto its first", source, name, i + 1));
              return;
            }
            if (previous ? overlap_beyond(all[k], seg, seg.source()) : CGAL::do_intersect(all[k], seg))
              throw InputError(
                  fmt::format("{}: crack '{}', segment {} meets {}; cracks do not cross, touch or fold back",
                              source, name, i + 1,
                              owner[k] == c ? std::string("an earlier segment of the same crack")
                                            : fmt::format("crack '{}'", names[owner[k]])));
          });
      all.push_back(seg);
      owner.push_back(c);
    }
    const int part = static_cast<int>(impl->part_names.size());
    impl->part_names.push_back(name);
    for (std::size_t i = 0; i + 1 < line.size(); ++i) {
      const Vec2 &a = line[i], &b = line[i + 1];
      const double length = (b - a).norm();
      const Vec2 t = (b - a) / length, right(t.y(), -t.x());
      const int crack_index = static_cast<int>(impl->cracks.size()), edge = static_cast<int>(i);
      impl->segments.push_back(BoundarySegment{a, b, right, length, -1, edge, part, crack_index});
      impl->segments.push_back(BoundarySegment{b, a, -right, length, -1, edge, part, crack_index});
    }
    impl->cracks.push_back(std::move(crack));
  }
  impl->grid = SegmentGrid(impl->segments);
  return Domain(std::move(impl));
}

Domain::Domain(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Domain::Domain(const Domain& other) : impl_(std::make_unique<Impl>(*other.impl_)) {}
Domain::Domain(Domain&&) noexcept = default;
Domain& Domain::operator=(const Domain& other) {
  if (this != &other) impl_ = std::make_unique<Impl>(*other.impl_);
  return *this;
}
Domain& Domain::operator=(Domain&&) noexcept = default;
Domain::~Domain() = default;

Domain Domain::rectangle(Vec2 lo, Vec2 hi) {
  if (!(lo.array() < hi.array()).all() || !lo.allFinite() || !hi.allFinite()) {
    throw InputError(fmt::format(
        "Domain::rectangle: need finite corners with lo < hi, got lo = ({}, {}), hi = ({}, {})",
        lo.x(), lo.y(), hi.x(), hi.y()));
  }
  Ring r{lo, Vec2(hi.x(), lo.y()), hi, Vec2(lo.x(), hi.y())};
  return Domain(std::make_unique<Impl>(std::vector<Ring>{std::move(r)}, std::vector<bool>{false},
                                       std::vector<std::vector<int>>{{0, 1, 2, 3}},
                                       std::vector<std::string>{"bottom", "right", "top", "left"}));
}

Domain Domain::from_rings(std::vector<Ring> rings, std::vector<std::vector<int>> edge_parts,
                          std::vector<std::string> part_names, const std::string& source) {
  if (rings.empty()) throw InputError(fmt::format("{}: no boundary rings", source));
  if (edge_parts.size() != rings.size())
    throw InputError(fmt::format("{}: {} rings but edge parts for {}", source, rings.size(), edge_parts.size()));
  for (const auto& ring : edge_parts)
    for (int p : ring)
      if (p < -1 || p >= static_cast<int>(part_names.size()))
        throw InputError(fmt::format("{}: edge part {} is not a named part (there are {})", source, p, part_names.size()));
  std::vector<bool> reversed;
  std::vector<Ring> oriented = normalised_rings(std::move(rings), source, reversed, &edge_parts);
  return Domain(std::make_unique<Impl>(std::move(oriented), reversed, edge_parts, std::move(part_names)));
}

namespace {

/// The ring clipped to the box `window` (Sutherland and Hodgman, double precision): the edges
/// inside the window as they are, the parts outside replaced by paths along its boundary.
/// Empty when no part of the ring's interior is in the window.
Ring clip_to_window(const Ring& ring, const Box& window) {
  Ring out = ring;
  for (int side = 0; side < 4 && !out.empty(); ++side) {
    const int axis = side % 2;
    const bool low = side < 2;
    const double at = low ? window.lo[axis] : window.hi[axis];
    const auto inside = [&](const Vec2& x) { return low ? x[axis] >= at : x[axis] <= at; };
    Ring in = std::move(out);
    out.clear();
    for (std::size_t i = 0; i < in.size(); ++i) {
      const Vec2 &a = in[i], &b = in[(i + 1) % in.size()];
      if (inside(a)) out.push_back(a);
      if (inside(a) != inside(b)) {
        Vec2 x = a + (at - a[axis]) / (b[axis] - a[axis]) * (b - a);
        x[axis] = at;
        out.push_back(x);
      }
    }
  }
  // Drop repeated vertices (a vertex on the window's boundary comes twice).
  out.erase(std::unique(out.begin(), out.end()), out.end());
  while (out.size() > 1 && out.front() == out.back()) out.pop_back();
  return out.size() >= 3 ? out : Ring{};
}

/// box ∩ the polygon of `rings` (outer ring first, holes after, oriented like rings()), as rings
/// oriented the same way; `outer_box` bounds the outer ring.
std::vector<Ring> clip_rings(const Box& box, const std::vector<Ring>& rings, const Box& outer_box) {
  if (!interiors_overlap(box, outer_box)) return {};
  // The exact intersection sweeps every edge of its polygons: a ring of thousands of edges
  // (a curved boundary from gmsh) costs a second a cell. Only the part of the polygon in a
  // window around the box matters: the outer ring is cut to the window first (holes that
  // reach out of the window leave the polygon whole), unless that leaves a ring that touches
  // itself (the polygon is in several pieces there).
  const Box window{box.lo - box.size(), box.hi + box.size()};
  std::vector<Ring> local{rings[0]};
  if (rings[0].size() > 32) {
    local[0] = clip_to_window(rings[0], window);
    if (local[0].empty()) return {};
  }
  bool whole = local[0].size() > 3 && !fast_polygon(local[0]).is_simple();
  for (std::size_t k = 1; k < rings.size() && !whole; ++k) {
    const Box hole = ring_bounding_box(rings[k]);
    if (!interiors_overlap(window, hole)) continue;
    if (window.contains(hole.lo) && window.contains(hole.hi))
      local.push_back(rings[k]);
    else
      whole = true;
  }
  if (whole) local = rings;
  // The exact polygons are built per call from the double rings, so concurrent calls share
  // no CGAL object. Holes whose boxes miss the box's interior cannot change the
  // (regularised) intersection and are left out of the sweep.
  ExactPolygonWithHoles omega(exact_polygon(local[0]));
  for (std::size_t k = 1; k < local.size(); ++k)
    if (interiors_overlap(box, ring_bounding_box(local[k]))) omega.add_hole(exact_polygon(local[k]));
  ExactPolygon cell;
  cell.push_back(Epeck::Point_2(box.lo.x(), box.lo.y()));
  cell.push_back(Epeck::Point_2(box.hi.x(), box.lo.y()));
  cell.push_back(Epeck::Point_2(box.hi.x(), box.hi.y()));
  cell.push_back(Epeck::Point_2(box.lo.x(), box.hi.y()));
  std::vector<ExactPolygonWithHoles> pieces;
  CGAL::intersection(omega, cell, std::back_inserter(pieces));
  // CGAL returns outer boundaries counter-clockwise and holes clockwise, as rings() does.
  std::vector<Ring> out;
  for (const ExactPolygonWithHoles& piece : pieces) {
    out.push_back(to_ring(piece.outer_boundary()));
    for (auto h = piece.holes_begin(); h != piece.holes_end(); ++h) out.push_back(to_ring(*h));
  }
  return out;
}

/// A piece of an edge two regions share, oriented along the edge of the first region (which
/// lies on its left).
struct SharedPiece {
  Vec2 a, b;
};

/// The pieces that edges of ring sets `first` and `second` share (collinear overlaps of
/// positive length, exact predicates), oriented along `first`'s edges.
std::vector<SharedPiece> shared_pieces(const std::vector<Ring>& first, const std::vector<Ring>& second) {
  std::vector<SharedPiece> out;
  for (const Ring& r : first)
    for (std::size_t i = 0; i < r.size(); ++i) {
      const Vec2 &a = r[i], &b = r[(i + 1) % r.size()];
      const Box box{a.cwiseMin(b), a.cwiseMax(b)};
      const Vec2 along = b - a;
      for (const Ring& q : second)
        for (std::size_t j = 0; j < q.size(); ++j) {
          const Vec2 &c = q[j], &e = q[(j + 1) % q.size()];
          if (c.cwiseMax(e).x() < box.lo.x() || c.cwiseMin(e).x() > box.hi.x() ||
              c.cwiseMax(e).y() < box.lo.y() || c.cwiseMin(e).y() > box.hi.y())
            continue;
          if (!CGAL::collinear(fast_point(a), fast_point(b), fast_point(c)) ||
              !CGAL::collinear(fast_point(a), fast_point(b), fast_point(e)))
            continue;
          // Along a -> b the overlap runs from the later start to the earlier end; its ends
          // are vertices of one ring or the other, so they are exact.
          const auto param = [&](const Vec2& x) { return (x - a).dot(along); };
          const Vec2& lo2 = param(c) < param(e) ? c : e;
          const Vec2& hi2 = param(c) < param(e) ? e : c;
          const Vec2& from = param(lo2) > 0.0 ? lo2 : a;
          const Vec2& to = param(hi2) < param(b) ? hi2 : b;
          if (param(to) > param(from)) out.push_back({from, to});
        }
    }
  return out;
}

/// Joins pieces end to start into polylines, open ones (from a start that no piece ends at)
/// first, then those that close on themselves (round an inclusion: the last point repeats the
/// first); throws naming `what` where they branch.
std::vector<std::vector<Vec2>> chain(const std::vector<SharedPiece>& pieces, const std::string& what) {
  const auto key = [](const Vec2& x) { return std::pair<double, double>(x.x(), x.y()); };
  std::map<std::pair<double, double>, std::size_t> starting;
  std::set<std::pair<double, double>> ends;
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    if (!starting.emplace(key(pieces[k].a), k).second)
      throw InputError(fmt::format("{} branches at ({}, {})", what, pieces[k].a.x(), pieces[k].a.y()));
    ends.insert(key(pieces[k].b));
  }
  std::vector<std::vector<Vec2>> lines;
  std::vector<char> used(pieces.size(), 0);
  const auto follow = [&](std::size_t first) {
    std::vector<Vec2> line{pieces[first].a};
    for (auto at = starting.find(key(line.back())); at != starting.end() && !used[at->second];
         at = starting.find(key(line.back()))) {
      line.push_back(pieces[at->second].b);
      used[at->second] = 1;
    }
    lines.push_back(std::move(line));
  };
  for (std::size_t k = 0; k < pieces.size(); ++k)
    if (!ends.count(key(pieces[k].a))) follow(k);  // the start of an open polyline
  for (std::size_t k = 0; k < pieces.size(); ++k)
    if (!used[k]) follow(k);  // a loop: it ends where it started
  return lines;
}

}  // namespace

Domain Domain::from_regions(std::vector<std::vector<Ring>> polygons, const RegionOptions& options,
                            const std::string& source, std::vector<std::vector<std::vector<int>>> edge_parts,
                            std::vector<std::string> part_names) {
  if (!edge_parts.empty() && edge_parts.size() != polygons.size())
    throw Error(
        fmt::format("{}: edge parts for {} of {} regions", source, edge_parts.size(), polygons.size()));
  std::vector<std::string> names = options.names;
  if (names.empty())
    for (std::size_t r = 0; r < polygons.size(); ++r) names.push_back(fmt::format("region{}", r + 1));
  if (names.size() != polygons.size())
    throw InputError(
        fmt::format("{}: {} region names for {} polygons", source, names.size(), polygons.size()));
  for (std::size_t r = 0; r < names.size(); ++r)
    if (names[r].empty() || std::find(names.begin(), names.begin() + r, names[r]) != names.begin() + r)
      throw InputError(fmt::format("{}: region name '{}' is {}", source, names[r],
                                   names[r].empty() ? "empty" : "given twice"));

  // Each region valid on its own, then their union one polygon with holes and no overlap.
  std::vector<Region> regions;
  std::vector<ExactPolygonWithHoles> exact;
  double area = 0.0;
  std::vector<SharedPiece> parted;  // region edges with a part, oriented
  std::vector<int> parted_as;       // and their parts
  // Every region edge's part (-1: none) by its ends, the lesser (x, then y) first.
  using EdgeKey = std::array<double, 4>;
  const auto edge_key = [](const Vec2& a, const Vec2& b) {
    const bool a_first = a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
    const Vec2 &p = a_first ? a : b, &q = a_first ? b : a;
    return EdgeKey{p.x(), p.y(), q.x(), q.y()};
  };
  std::map<EdgeKey, int> part_of_edge;
  for (std::size_t r = 0; r < polygons.size(); ++r) {
    std::vector<bool> reversed;
    Region region{names[r],
                  normalised_rings(std::move(polygons[r]), fmt::format("{}, region '{}'", source, names[r]),
                                   reversed, edge_parts.empty() ? nullptr : &edge_parts[r])};
    for (std::size_t k = 0; !edge_parts.empty() && k < region.rings.size(); ++k) {
      const Ring& ring = region.rings[k];
      const std::size_t n = ring.size();
      for (std::size_t i = 0; i < n; ++i) {
        const int part = edge_parts[r][k][reversed[k] ? (2 * n - 2 - i) % n : i];
        if (part < -1 || part >= static_cast<int>(part_names.size()))
          throw InputError(fmt::format("{}: edge part {} is not a named part (there are {})", source, part,
                                       part_names.size()));
        part_of_edge.emplace(edge_key(ring[i], ring[(i + 1) % n]), part);
        if (part < 0) continue;
        parted.push_back({ring[i], ring[(i + 1) % n]});
        parted_as.push_back(part);
      }
    }
    ExactPolygonWithHoles p(exact_polygon(region.rings[0]));
    for (std::size_t k = 1; k < region.rings.size(); ++k) p.add_hole(exact_polygon(region.rings[k]));
    exact.push_back(std::move(p));
    for (const Ring& ring : region.rings) area += ring_area(ring);
    regions.push_back(std::move(region));
  }
  std::vector<ExactPolygonWithHoles> joined;
  CGAL::join(exact.begin(), exact.end(), std::back_inserter(joined));
  if (joined.size() != 1)
    throw InputError(
        fmt::format("{}: the {} regions make {} separate pieces; regions of one domain share edges", source,
                    regions.size(), joined.size()));
  std::vector<Ring> rings{to_ring(joined[0].outer_boundary())};
  for (auto h = joined[0].holes_begin(); h != joined[0].holes_end(); ++h) rings.push_back(to_ring(*h));
  // Each edge of the union lies along an edge of a region: it takes that edge's part. Most are
  // a region's edge itself; the others (pieces of one, split where another region's vertex
  // touches it) are sought among the edges with a part.
  std::vector<std::vector<int>> union_parts;
  for (const Ring& ring : rings) {
    std::vector<int>& parts = union_parts.emplace_back(ring.size(), -1);
    for (std::size_t i = 0; i < ring.size() && !parted.empty(); ++i) {
      const Vec2 &a = ring[i], &b = ring[(i + 1) % ring.size()];
      if (const auto same = part_of_edge.find(edge_key(a, b)); same != part_of_edge.end()) {
        parts[i] = same->second;
        continue;
      }
      const Box box{a.cwiseMin(b), a.cwiseMax(b)};
      for (std::size_t e = 0; e < parted.size(); ++e) {
        const Vec2 &c = parted[e].a, &d = parted[e].b;
        if (box.lo.x() < std::min(c.x(), d.x()) || box.hi.x() > std::max(c.x(), d.x()) ||
            box.lo.y() < std::min(c.y(), d.y()) || box.hi.y() > std::max(c.y(), d.y()))
          continue;  // a -> b does not lie within c -> d's box
        if (CGAL::collinear(fast_point(c), fast_point(d), fast_point(a)) &&
            CGAL::collinear(fast_point(c), fast_point(d), fast_point(b)) && (a - c).dot(d - c) >= 0.0 &&
            (b - c).dot(d - c) >= 0.0 && (a - d).dot(c - d) >= 0.0 && (b - d).dot(c - d) >= 0.0) {
          parts[i] = parted_as[e];
          break;
        }
      }
    }
  }
  std::vector<bool> reversed;
  std::vector<Ring> oriented =
      normalised_rings(std::move(rings), source + " (the union of its regions)", reversed, &union_parts);
  auto impl = std::make_unique<Impl>(std::move(oriented), reversed, union_parts, std::move(part_names));
  if (std::abs(impl->area - area) > 1e-12 * area)
    throw InputError(
        fmt::format("{}: the regions overlap (their areas add up to {:.10g}, their union has {:.10g})",
                    source, area, impl->area));
  for (const Region& region : regions) {
    std::vector<FastPolygon> fast;
    for (const Ring& ring : region.rings) fast.push_back(fast_polygon(ring));
    impl->region_polygons.push_back(std::move(fast));
    impl->region_boxes.push_back(ring_bounding_box(region.rings[0]));
  }
  impl->regions = std::move(regions);
  Domain domain(std::move(impl));
  if (!options.interfaces) return domain;

  // The interfaces: per pair of regions, the edges they share, joined into polylines.
  const std::vector<Region>& all = domain.regions();
  std::vector<std::vector<Vec2>> lines;
  std::vector<std::string> line_names;
  std::vector<std::pair<int, int>> sides;
  for (std::size_t i = 0; i < all.size(); ++i)
    for (std::size_t j = i + 1; j < all.size(); ++j) {
      const std::string name = fmt::format("{}/{}", all[i].name, all[j].name);
      for (std::vector<Vec2>& line : chain(shared_pieces(all[i].rings, all[j].rings),
                                           fmt::format("{}: the interface '{}'", source, name))) {
        lines.push_back(std::move(line));
        line_names.push_back(name);
        sides.emplace_back(static_cast<int>(i), static_cast<int>(j));
      }
    }
  // An interface in several pieces gets a number per piece.
  std::map<std::string, int> pieces, numbered;
  for (const std::string& n : line_names) ++pieces[n];
  for (std::string& n : line_names)
    if (const std::string base = n; pieces[base] > 1) n += fmt::format("#{}", ++numbered[base]);
  return domain.with_cracks(std::move(lines), std::move(line_names), source, sides);
}

Domain Domain::from_wkt(std::string_view wkt, const std::string& source, const RegionOptions& regions) {
  WktReader reader(wkt, source);
  WktGeometry g = reader.geometry();
  Domain domain = [&] {
    if (g.polygons.size() > 1 || !regions.names.empty())
      return from_regions(std::move(g.polygons), regions, source);
    std::vector<bool> reversed;
    std::vector<Ring> oriented = normalised_rings(std::move(g.polygons.front()), source, reversed);
    return Domain(std::make_unique<Impl>(std::move(oriented), reversed));
  }();
  if (g.lines.empty()) return domain;
  std::vector<std::string> names;
  for (std::size_t c = 0; c < g.lines.size(); ++c) names.push_back(fmt::format("crack{}", c + 1));
  return domain.with_cracks(std::move(g.lines), std::move(names), source);
}

Domain Domain::from_file(const std::filesystem::path& path, const RegionOptions& regions) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw InputError(fmt::format("mesh file '{}' does not exist or is not a regular file",
                                 path.string()));
  }
  constexpr std::uintmax_t max_bytes = std::uintmax_t{1} << 30;
  if (const std::uintmax_t bytes = std::filesystem::file_size(path, ec); !ec && bytes > max_bytes)
    throw InputError(fmt::format("mesh file '{}' is {} bytes, more than the {} a domain file may have", path.string(),
                                 bytes, max_bytes));
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (is_gmsh_file(path)) {
    if (!regions.names.empty())
      throw InputError(
          fmt::format("mesh file '{}': a gmsh file names its regions (physical surfaces); "
                      "region names are for WKT files",
                      path.string()));
    return read_gmsh_domain(path, default_gmsh_reader_limits(), regions.interfaces);
  }
  if (extension != ".wkt") {
    std::string accepted = ".wkt";
    for (const std::string_view e : gmsh_extensions) accepted += fmt::format(", {}", e);
    throw InputError(fmt::format("mesh file '{}': unknown extension '{}'; mfree reads {} (WKT, or gmsh "
                                 "scripts, meshes and CAD files)",
                                 path.string(), path.extension().string(), accepted));
  }
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in || !text) {
    throw InputError(fmt::format("cannot read mesh file '{}'", path.string()));
  }
  return from_wkt(text.str(), path.string(), regions);
}

bool Domain::contains(const Vec2& x) const {
  const Impl& d = *impl_;
  if (!d.box.contains(x)) return false;
  const Epick::Point_2 p = fast_point(x);
  if (d.fast_rings[0].bounded_side(p) == CGAL::ON_UNBOUNDED_SIDE) return false;
  for (std::size_t k = 1; k < d.fast_rings.size(); ++k) {
    // The hole's boundary belongs to the closed domain; only its open interior is excluded.
    if (d.ring_boxes[k].contains(x) && d.fast_rings[k].bounded_side(p) == CGAL::ON_BOUNDED_SIDE)
      return false;
  }
  return true;
}

double Domain::area() const { return impl_->area; }
Vec2 Domain::first_moment() const { return impl_->first_moment; }
Box Domain::bounding_box() const { return impl_->box; }
const std::vector<Ring>& Domain::rings() const { return impl_->rings; }
const std::vector<BoundarySegment>& Domain::boundary() const { return impl_->segments; }
const std::vector<std::string>& Domain::part_names() const { return impl_->part_names; }
const std::vector<Crack>& Domain::cracks() const { return impl_->cracks; }
const std::vector<Region>& Domain::regions() const { return impl_->regions; }
std::pair<int, double> Domain::nearest_region(const Vec2& x) const {
  if (const int r = region_at(x); r >= 0) return {r, 0.0};
  std::pair<int, double> best{-1, std::numeric_limits<double>::infinity()};
  for (std::size_t r = 0; r < impl_->regions.size(); ++r)
    for (const Ring& ring : impl_->regions[r].rings)
      for (std::size_t i = 0; i < ring.size(); ++i) {
        const Vec2 &a = ring[i], d = ring[(i + 1) % ring.size()] - a;
        const double t = std::clamp((x - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
        if (const double e = (a + t * d - x).norm(); e < best.second) best = {static_cast<int>(r), e};
      }
  return best;
}

bool Domain::boundary_near(const Box& box) const { return impl_->grid.may_touch(box); }

std::vector<int> Domain::boundary_segments_near(const Box& box) const {
  std::vector<int> out;
  impl_->grid.for_each_meeting(box, [&](int k) { out.push_back(k); });
  return out;
}

int Domain::region_at(const Vec2& x) const {
  const Impl& d = *impl_;
  if (d.regions.empty()) return 0;
  const Epick::Point_2 p = fast_point(x);
  for (std::size_t r = 0; r < d.regions.size(); ++r) {
    if (!d.region_boxes[r].contains(x)) continue;
    const std::vector<FastPolygon>& rings = d.region_polygons[r];
    if (rings[0].bounded_side(p) == CGAL::ON_UNBOUNDED_SIDE) continue;
    if (std::none_of(rings.begin() + 1, rings.end(),
                     [&](const FastPolygon& h) { return h.bounded_side(p) == CGAL::ON_BOUNDED_SIDE; }))
      return static_cast<int>(r);
  }
  return -1;
}

std::vector<Ring> Domain::clip(const Box& box, int region) const {
  const Impl& d = *impl_;
  if (region >= 0) {
    const std::size_t r = static_cast<std::size_t>(region);
    if (r >= d.regions.size()) throw Error(fmt::format("Domain::clip: no region {}", region));
    return clip_rings(box, d.regions[r].rings, d.region_boxes[r]);
  }
  if (!interiors_overlap(box, d.box)) return {};
  if (box.contains(d.box.lo) && box.contains(d.box.hi)) return d.rings;
  // A box the boundary cannot reach is wholly inside or wholly outside (segment_grid.hpp).
  if (!d.grid.may_touch(box)) {
    if (!contains(0.5 * (box.lo + box.hi))) return {};
    return {Ring{box.lo, Vec2(box.hi.x(), box.lo.y()), box.hi, Vec2(box.lo.x(), box.hi.y())}};
  }
  return clip_rings(box, d.rings, d.box);
}

}  // namespace mfree
