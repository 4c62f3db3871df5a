#pragma once
// Buckets of boundary segments on a uniform grid, for the question "can any boundary
// segment meet this box?", asked once per background cell or Voronoi cell.
//
// The test compares the box with each nearby segment's bounding box, so a "no" is
// certain (the closed box holds no boundary point) and a "yes" only means "maybe".
// A region whose box the boundary cannot meet lies wholly inside or wholly outside the
// domain, and one point of it decides which.

#include <vector>

#include "mfree/core/types.hpp"
#include "mfree/geometry/domain.hpp"

namespace mfree {

class SegmentGrid {
 public:
  explicit SegmentGrid(const std::vector<BoundarySegment>& segments);

  /// False only if no segment's bounding box meets the closed box.
  [[nodiscard]] bool may_touch(const Box& box) const;

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
