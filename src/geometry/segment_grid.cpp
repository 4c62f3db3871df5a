#include "mfree/geometry/segment_grid.hpp"

#include <algorithm>
#include <cmath>

namespace mfree {

SegmentGrid::SegmentGrid(const std::vector<BoundarySegment>& segments) {
  boxes_.reserve(segments.size());
  for (const BoundarySegment& s : segments) {
    boxes_.push_back(Box{s.a.cwiseMin(s.b), s.a.cwiseMax(s.b)});
  }
  if (boxes_.empty()) {
    extent_ = Box{Vec2::Zero(), Vec2::Zero()};
    cell_ = Vec2::Ones();
    start_.assign(2, 0);
    return;
  }
  extent_ = boxes_[0];
  for (const Box& b : boxes_) {
    extent_.lo = extent_.lo.cwiseMin(b.lo);
    extent_.hi = extent_.hi.cwiseMax(b.hi);
  }
  // About one bucket per segment, shaped like the extent, so a bucket holds O(1) segments
  // of a boundary whose edges have comparable lengths.
  // A flat extent (segments along one line: a straight crack) gets a side of 1e-6 of the
  // other, so the aspect ratio and the bucket counts stay finite.
  const Vec2 size = extent_.size().cwiseMax(1e-6 * std::max(extent_.size().maxCoeff(), 1e-300));
  const double n = static_cast<double>(boxes_.size());
  const double aspect = size.x() / size.y();
  constexpr int max_side = 2048;
  nx_ = std::clamp(static_cast<int>(std::lround(std::sqrt(n * aspect))), 1, max_side);
  ny_ = std::clamp(static_cast<int>(std::lround(n / nx_)), 1, max_side);
  cell_ = Vec2(size.x() / nx_, size.y() / ny_);

  // Counting sort into compressed rows: count, prefix-sum, fill.
  start_.assign(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
  auto for_buckets = [&](const Box& b, auto&& f) {
    for (int j = row(b.lo.y()); j <= row(b.hi.y()); ++j)
      for (int i = column(b.lo.x()); i <= column(b.hi.x()); ++i) f(j * nx_ + i);
  };
  for (const Box& b : boxes_) for_buckets(b, [&](int k) { ++start_[k + 1]; });
  for (std::size_t k = 1; k < start_.size(); ++k) start_[k] += start_[k - 1];
  items_.resize(static_cast<std::size_t>(start_.back()));
  std::vector<int> fill(start_.begin(), start_.end() - 1);
  for (int s = 0; s < static_cast<int>(boxes_.size()); ++s)
    for_buckets(boxes_[s], [&](int k) { items_[fill[k]++] = s; });
}

// Bucket coordinates are monotone in x (subtraction and division by a positive constant
// are monotone under rounding), so two overlapping closed intervals always share a bucket.
int SegmentGrid::column(double x) const {
  return std::clamp(static_cast<int>(std::floor((x - extent_.lo.x()) / cell_.x())), 0, nx_ - 1);
}

int SegmentGrid::row(double y) const {
  return std::clamp(static_cast<int>(std::floor((y - extent_.lo.y()) / cell_.y())), 0, ny_ - 1);
}

bool SegmentGrid::may_touch(const Box& box) const {
  if (items_.empty()) return false;
  if (box.hi.x() < extent_.lo.x() || box.lo.x() > extent_.hi.x() ||
      box.hi.y() < extent_.lo.y() || box.lo.y() > extent_.hi.y())
    return false;
  for (int j = row(box.lo.y()); j <= row(box.hi.y()); ++j) {
    for (int i = column(box.lo.x()); i <= column(box.hi.x()); ++i) {
      const int k = j * nx_ + i;
      for (int m = start_[k]; m < start_[k + 1]; ++m) {
        const Box& b = boxes_[items_[m]];
        if (b.lo.x() <= box.hi.x() && box.lo.x() <= b.hi.x() && b.lo.y() <= box.hi.y() &&
            box.lo.y() <= b.hi.y())
          return true;
      }
    }
  }
  return false;
}

}  // namespace mfree
