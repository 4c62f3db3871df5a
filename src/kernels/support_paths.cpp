#include "mfree/kernels/support_paths.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "mfree/core/error.hpp"
#include "mfree/core/parallel.hpp"
#include "mfree/search/cell_list.hpp"

namespace mfree {

const NameTable<SupportRule>& support_rule_names() {
  static const NameTable<SupportRule> table{{"plain", SupportRule::plain},
                                            {"visibility", SupportRule::visibility},
                                            {"geodesic", SupportRule::geodesic}};
  return table;
}

std::string_view to_string(SupportRule rule) { return support_rule_names().name(rule); }

namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();

/// Whether the open segments p q and a b cross at one point interior to both: touching at an
/// end or running along each other is not crossing. An end within `tolerance` (a length) of
/// the other segment's line counts as lying on it: a point on a boundary edge whose
/// coordinates carry round-off (a lattice at h = 0.1 puts y = -1 + 10 h = 5.6e-17 on the
/// face y = 0) touches the edge and is seen from the domain's side, not cut off from it.
bool crosses(const Vec2& p, const Vec2& q, const Vec2& a, const Vec2& b, double tolerance) {
  // orientation / length: signed distance from the line (length units).
  const double o1 = orientation(a, b, p), o2 = orientation(a, b, q);
  if (!(o1 * o2 < 0.0)) return false;  // the common case, before any square root
  const double ab = tolerance * (b - a).norm();
  if (!((o1 > ab && o2 < -ab) || (o1 < -ab && o2 > ab))) return false;
  const double o3 = orientation(p, q, a), o4 = orientation(p, q, b), pq = tolerance * (q - p).norm();
  return (o3 > pq && o4 < -pq) || (o3 < -pq && o4 > pq);
}

/// Whether the segment p q starts on the open edge a b (to `tolerance`, away from its ends,
/// where the other edge of the vertex decides) and leaves it to the right, the outside of a
/// ring edge: from a point on one face of a re-entrant corner to a point on the other, the
/// segment runs outside and touches the edges only at its ends.
bool leaves_outside(const Vec2& p, const Vec2& q, const Vec2& a, const Vec2& b, double tolerance) {
  const Vec2 e = b - a;
  const double off = orientation(a, b, p), length2 = e.squaredNorm();
  if (!(off * off <= tolerance * tolerance * length2)) return false;  // before any square root
  const double length = std::sqrt(length2), along = (p - a).dot(e);
  if (!(along > tolerance * length && along < (length - tolerance) * length)) return false;
  return orientation(a, b, q) < -tolerance * length;
}

/// Whether the segment p q (direction d = q - p, length `length`) passes through or starts
/// at the reflex vertex v (to `tolerance`) and runs into its outside wedge, the convex cone of
/// the unit edge directions e (to 1e-10 in the sines: along an edge is not into it).
bool enters_wedge(const Vec2& p, const Vec2& q, const Vec2& v, const std::array<Vec2, 2>& e,
                  double tolerance) {
  const Vec2 d = q - p;
  const double length = d.norm();
  if (!(length > 0.0) || !(std::abs(orientation(p, q, v)) <= tolerance * length)) return false;
  const double along = (v - p).dot(d) / length;
  if (along < -tolerance || along > length + tolerance) return false;
  const double turn = e[0].x() * e[1].y() - e[0].y() * e[1].x();
  const auto inside = [&](const Vec2& u) {
    const double s0 = e[0].x() * u.y() - e[0].y() * u.x(), s1 = u.x() * e[1].y() - u.y() * e[1].x();
    return turn > 0.0 ? s0 > 1e-10 && s1 > 1e-10 : s0 < -1e-10 && s1 < -1e-10;
  };
  const Vec2 u = d / length;
  if (along <= tolerance) return inside(u);            // from v
  if (along >= length - tolerance) return inside(-u);  // to v
  return inside(u) || inside(-u);                      // through v
}

Vec2 unit_or_zero(const Vec2& v) {
  const double n = v.norm();
  return n > 0.0 ? Vec2(v / n) : Vec2(Vec2::Zero());
}

}  // namespace

SupportPaths::SupportPaths(SupportObstacles obstacles, SupportRule rule, double reach)
    : obstacles_(std::move(obstacles)), rule_(rule), reach_(reach) {
  if (!(reach_ > 0.0) || !std::isfinite(reach_))
    throw InputError(fmt::format("support paths: the reach must be positive, got {}", reach_));
  if (obstacles_.a.size() != obstacles_.b.size())
    throw Error(fmt::format("support paths: {} segment starts for {} ends", obstacles_.a.size(),
                            obstacles_.b.size()));
  if (obstacles_.empty()) return;

  Box box{obstacles_.a[0], obstacles_.a[0]};
  const auto grow = [&](const Vec2& x) {
    box.lo = box.lo.cwiseMin(x);
    box.hi = box.hi.cwiseMax(x);
  };
  for (std::size_t k = 0; k < obstacles_.a.size(); ++k) {
    grow(obstacles_.a[k]);
    grow(obstacles_.b[k]);
  }
  for (const Vec2& c : obstacles_.corners) grow(c);
  // Round-off of coordinates of this size: 1e-12 of the largest coordinate or extent.
  tolerance_ =
      1e-12 * std::max({box.size().norm(), box.lo.cwiseAbs().maxCoeff(), box.hi.cwiseAbs().maxCoeff()});
  // Buckets of side reach (at most 2048 per axis), so a query looks at 3 x 3 of them.
  side_ = std::max({reach_, box.size().x() / 2048.0, box.size().y() / 2048.0});
  const double side = side_;
  origin_ = box.lo;
  nx_ = static_cast<int>(box.size().x() / side) + 1;
  ny_ = static_cast<int>(box.size().y() / side) + 1;
  const auto bucket_range = [&](const Vec2& lo, const Vec2& hi, int& i0, int& i1, int& j0, int& j1) {
    i0 = std::clamp(static_cast<int>((lo.x() - origin_.x()) / side), 0, nx_ - 1);
    i1 = std::clamp(static_cast<int>((hi.x() - origin_.x()) / side), 0, nx_ - 1);
    j0 = std::clamp(static_cast<int>((lo.y() - origin_.y()) / side), 0, ny_ - 1);
    j1 = std::clamp(static_cast<int>((hi.y() - origin_.y()) / side), 0, ny_ - 1);
  };
  // Two passes (count, fill) into CSR buckets.
  const auto fill = [&](std::size_t n, auto&& extent, std::vector<int>& start, std::vector<int>& items) {
    start.assign(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
    for (int pass = 0; pass < 2; ++pass) {
      std::vector<int> cursor(start.begin(), start.end() - 1);
      for (std::size_t k = 0; k < n; ++k) {
        Vec2 lo, hi;
        extent(k, lo, hi);
        int i0, i1, j0, j1;
        bucket_range(lo, hi, i0, i1, j0, j1);
        for (int j = j0; j <= j1; ++j)
          for (int i = i0; i <= i1; ++i) {
            const std::size_t cell = static_cast<std::size_t>(j) * nx_ + i;
            if (pass == 0)
              ++start[cell + 1];
            else
              items[cursor[cell]++] = static_cast<int>(k);
          }
      }
      if (pass == 0) {
        for (std::size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
        items.resize(start.back());
      }
    }
  };
  fill(
      obstacles_.a.size(),
      [&](std::size_t k, Vec2& lo, Vec2& hi) {
        lo = obstacles_.a[k].cwiseMin(obstacles_.b[k]);
        hi = obstacles_.a[k].cwiseMax(obstacles_.b[k]);
      },
      segment_start_, segment_items_);
  fill(
      obstacles_.corners.size(), [&](std::size_t k, Vec2& lo, Vec2& hi) { lo = hi = obstacles_.corners[k]; },
      corner_start_, corner_items_);
  fill(
      obstacles_.wedge_vertex.size(),
      [&](std::size_t k, Vec2& lo, Vec2& hi) { lo = hi = obstacles_.wedge_vertex[k]; }, wedge_start_,
      wedge_items_);
  if (rule_ == SupportRule::geodesic) find_legs();
}

void SupportPaths::find_legs() {
  // Per corner p, the corners q after it within the reach joined by a leg; each leg is then
  // stored at both ends. The same point, so the same obstacles, for all of p's legs.
  const Index n = static_cast<Index>(obstacles_.corners.size());
  std::vector<std::vector<std::pair<int, double>>> after(n);
  parallel_blocks(n, 16, [&](Index begin, Index end) {
    PathScratch s;
    for (Index c = begin; c < end; ++c) {
      const Vec2& p = obstacles_.corners[c];
      if (!prepare_obstacles(p, s)) continue;
      for (const int d : s.corners) {
        if (d <= c) continue;
        const Vec2& q = obstacles_.corners[d];
        const double length = (q - p).norm();
        if (length < reach_ && obstacles_.reaches(q, c) && obstacles_.reaches(p, d) && visible(p, q, s))
          after[c].emplace_back(d, length);
      }
    }
  });
  leg_start_.assign(n + 1, 0);
  for (Index c = 0; c < n; ++c)
    for (const auto& [d, length] : after[c]) {
      ++leg_start_[c + 1];
      ++leg_start_[d + 1];
    }
  for (Index c = 0; c < n; ++c) leg_start_[c + 1] += leg_start_[c];
  leg_to_.resize(leg_start_[n]);
  leg_length_.resize(leg_start_[n]);
  std::vector<int> cursor(leg_start_.begin(), leg_start_.end() - 1);
  const auto store = [&](int from, int to, double length) {
    leg_to_[cursor[from]] = to;
    leg_length_[cursor[from]++] = length;
  };
  for (Index c = 0; c < n; ++c)
    for (const auto& [d, length] : after[c]) {
      store(static_cast<int>(c), d, length);
      store(d, static_cast<int>(c), length);
    }
}

template <class F>
void SupportPaths::for_each_bucket(const Vec2& x, F&& f) const {
  const double side = side_;
  const auto cell = [&](double v, double o, int n) {
    const double t = std::floor((v - o) / side);
    return static_cast<int>(std::clamp(t, 0.0, static_cast<double>(n - 1)));
  };
  const int i0 = cell(x.x() - reach_, origin_.x(), nx_), i1 = cell(x.x() + reach_, origin_.x(), nx_);
  const int j0 = cell(x.y() - reach_, origin_.y(), ny_), j1 = cell(x.y() + reach_, origin_.y(), ny_);
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) f(static_cast<std::size_t>(j) * nx_ + i);
}

bool SupportPaths::prepare_obstacles(const Vec2& x, PathScratch& s) const {
  s.segments.clear();
  s.corners.clear();
  s.wedges.clear();
  // The box x +- reach: any obstacle a path within the support can meet lies in it.
  const Vec2 lo = x.array() - reach_, hi = x.array() + reach_;
  for_each_bucket(x, [&](std::size_t cell) {
    for (int i = segment_start_[cell]; i < segment_start_[cell + 1]; ++i) {
      const int k = segment_items_[i];
      const Vec2 &a = obstacles_.a[k], &b = obstacles_.b[k];
      if (std::max(a.x(), b.x()) < lo.x() || std::min(a.x(), b.x()) > hi.x() ||
          std::max(a.y(), b.y()) < lo.y() || std::min(a.y(), b.y()) > hi.y())
        continue;
      s.segments.push_back(k);
    }
    for (int i = corner_start_[cell]; i < corner_start_[cell + 1]; ++i) {
      const int k = corner_items_[i];
      if ((obstacles_.corners[k] - x).squaredNorm() < reach_ * reach_) s.corners.push_back(k);
    }
    for (int i = wedge_start_[cell]; i < wedge_start_[cell + 1]; ++i) {
      const int k = wedge_items_[i];
      if ((obstacles_.wedge_vertex[k] - x).squaredNorm() <= reach_ * reach_) s.wedges.push_back(k);
    }
  });
  if (s.segments.empty()) return false;
  // A segment spanning several buckets was met once per bucket.
  std::sort(s.segments.begin(), s.segments.end());
  s.segments.erase(std::unique(s.segments.begin(), s.segments.end()), s.segments.end());
  return true;
}

bool SupportPaths::prepare(const Vec2& x, PathScratch& s) const {
  if (rule_ == SupportRule::plain || obstacles_.empty()) {
    s.segments.clear();
    s.corners.clear();
    s.wedges.clear();
    return false;
  }
  if (!prepare_obstacles(x, s)) return false;
  if (rule_ != SupportRule::geodesic) return true;

  // Shortest paths from x to the near corners: Dijkstra over the first legs, from x to the
  // corners it sees, and the legs between corners (find_legs).
  const std::size_t n = s.corners.size();
  s.to_x.assign(n, infinity);
  s.last.assign(n, x);
  s.local.resize(obstacles_.corners.size(), -1);
  s.heap.clear();
  const auto later = [](const std::pair<double, int>& u, const std::pair<double, int>& v) { return u > v; };
  for (std::size_t c = 0; c < n; ++c) {
    s.local[s.corners[c]] = static_cast<int>(c);
    const Vec2& p = obstacles_.corners[s.corners[c]];
    if (obstacles_.reaches(x, s.corners[c]) && visible(x, p, s)) {
      s.to_x[c] = (p - x).norm();
      s.last[c] = p;
      s.heap.emplace_back(s.to_x[c], static_cast<int>(c));
    }
  }
  std::make_heap(s.heap.begin(), s.heap.end(), later);
  while (!s.heap.empty()) {
    std::pop_heap(s.heap.begin(), s.heap.end(), later);
    const auto [length, c] = s.heap.back();
    s.heap.pop_back();
    if (length > s.to_x[c]) continue;  // a shorter path to c came first
    const int corner = s.corners[c];
    for (int l = leg_start_[corner]; l < leg_start_[corner + 1]; ++l) {
      const int to = s.local[leg_to_[l]];
      const double through = length + leg_length_[l];
      if (to < 0 || !(through < s.to_x[to] && through < reach_)) continue;
      s.to_x[to] = through;
      s.last[to] = s.last[c];
      s.heap.emplace_back(through, to);
      std::push_heap(s.heap.begin(), s.heap.end(), later);
    }
  }
  for (const int corner : s.corners) s.local[corner] = -1;
  return true;
}

bool SupportPaths::visible(const Vec2& p, const Vec2& q, const PathScratch& s) const {
  // The box of p q grown by the tolerance: an obstacle apart from it neither crosses nor
  // holds an end of p q.
  const double grow = tolerance_ + 1e-12 * (q - p).lpNorm<Eigen::Infinity>();
  const Vec2 lo = p.cwiseMin(q).array() - grow, hi = p.cwiseMax(q).array() + grow;
  for (const int k : s.segments) {
    const Vec2 &a = obstacles_.a[k], &b = obstacles_.b[k];
    if (std::max(a.x(), b.x()) < lo.x() || std::min(a.x(), b.x()) > hi.x() || std::max(a.y(), b.y()) < lo.y() ||
        std::min(a.y(), b.y()) > hi.y())
      continue;
    if (crosses(p, q, a, b, tolerance_)) return false;
    if (!obstacles_.one_sided.empty() && obstacles_.one_sided[k] &&
        (leaves_outside(p, q, a, b, tolerance_) || leaves_outside(q, p, a, b, tolerance_)))
      return false;
  }
  for (const int k : s.wedges) {
    const Vec2& v = obstacles_.wedge_vertex[k];
    if (v.x() < lo.x() || v.x() > hi.x() || v.y() < lo.y() || v.y() > hi.y()) continue;
    if (enters_wedge(p, q, v, obstacles_.wedge_edges[k], tolerance_)) return false;
  }
  return true;
}

double SupportPaths::distance(const Vec2& xi, const Vec2& x, const PathScratch& s, Vec2& gradient) const {
  if (visible(xi, x, s)) {
    gradient = unit_or_zero(x - xi);
    return (x - xi).norm();
  }
  gradient = Vec2::Zero();
  if (rule_ != SupportRule::geodesic) return infinity;
  double best = infinity;
  for (std::size_t c = 0; c < s.corners.size(); ++c) {
    if (!(s.to_x[c] < reach_)) continue;
    const Vec2& p = obstacles_.corners[s.corners[c]];
    const double d = s.to_x[c] + (p - xi).norm();
    if (d < best && d < reach_ && obstacles_.reaches(xi, s.corners[c]) && visible(xi, p, s)) {
      best = d;
      gradient = unit_or_zero(x - s.last[c]);
    }
  }
  return best;
}

std::optional<Bridge> find_bridge(const std::vector<Vec2>& nodes, const std::vector<Vec2>& points,
                                  const SupportObstacles& obstacles, double radius) {
  if (obstacles.empty() || nodes.empty()) return std::nullopt;
  // Paths searched up to 2 radii: a node within the radius whose path is longer bridges.
  const SupportPaths paths(obstacles, SupportRule::geodesic, 2.0 * radius);
  const CellList<2> cells(nodes, radius);
  const Index n = static_cast<Index>(points.size());
  std::vector<std::optional<Bridge>> found(points.size());
  parallel_blocks(n, 256, [&](Index begin, Index end) {
    PathScratch scratch;
    for (Index k = begin; k < end; ++k) {
      const Vec2& x = points[k];
      if (!paths.prepare(x, scratch)) continue;
      cells.for_each_in_box(x, radius, [&](Index, const Vec2& p) {
        const double straight = (p - x).norm();
        if (found[k] || !(straight < radius)) return;
        Vec2 gradient;
        const double d = paths.distance(p, x, scratch, gradient);
        if (d > 2.0 * straight) found[k] = Bridge{p, x, straight, d};
      });
    }
  });
  for (const std::optional<Bridge>& b : found)
    if (b) return b;
  return std::nullopt;
}

}  // namespace mfree
