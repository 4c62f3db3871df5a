#pragma once
// Buckets of boundary segments on a uniform grid, for the question "can any boundary
// segment meet this box?", asked once per background cell or Voronoi cell.
//
// The test compares the box with each nearby segment's bounding box, so a "no" is
// certain (the closed box holds no boundary point) and a "yes" only means "maybe".
// A region whose box the boundary cannot meet lies wholly inside or wholly outside the
// domain, and one point of it decides which.

#include <algorithm>
#include <vector>

#include "mfree/core/types.hpp"
#include "mfree/geometry/domain.hpp"

namespace mfree {

class SegmentGrid {
 public:
  explicit SegmentGrid(const std::vector<BoundarySegment>& segments);

  /// False only if no segment's bounding box meets the closed box.
  [[nodiscard]] bool may_touch(const Box& box) const;

  /// Calls f(index) once for every segment whose bounding box meets the closed box.
  template <class F>
  void for_each_meeting(const Box& box, F&& f) const {
    if (items_.empty() || box.hi.x() < extent_.lo.x() || box.lo.x() > extent_.hi.x() ||
        box.hi.y() < extent_.lo.y() || box.lo.y() > extent_.hi.y())
      return;
    const int i0 = column(box.lo.x()), j0 = row(box.lo.y());
    for (int j = j0; j <= row(box.hi.y()); ++j)
      for (int i = i0; i <= column(box.hi.x()); ++i) {
        const int k = j * nx_ + i;
        for (int m = start_[k]; m < start_[k + 1]; ++m) {
          const Box& b = boxes_[items_[m]];
          if (b.lo.x() > box.hi.x() || box.lo.x() > b.hi.x() || b.lo.y() > box.hi.y() ||
              box.lo.y() > b.hi.y())
            continue;
          // Reported from the first bucket the two boxes share only.
          if (i == std::max(i0, column(b.lo.x())) && j == std::max(j0, row(b.lo.y()))) f(items_[m]);
        }
      }
  }

 private:
  [[nodiscard]] int column(double x) const;
  [[nodiscard]] int row(double y) const;

  Box extent_;                // bounding box of all segments
  int nx_ = 1, ny_ = 1;       // grid size
  Vec2 cell_;                 // bucket size
  std::vector<Box> boxes_;    // bounding box of each segment
  std::vector<int> start_;    // bucket b holds items_[start_[b] .. start_[b + 1])
  std::vector<int> items_;    // segment indices, bucket by bucket
};

}  // namespace mfree
