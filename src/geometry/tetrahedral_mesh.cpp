#include "mfree/geometry/tetrahedral_mesh.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "mfree/core/error.hpp"

namespace mfree {

namespace {
std::string point_text(const Point<3>& x) { return fmt::format("{}, {}, {}", x.x(), x.y(), x.z()); }
}  // namespace

TetrahedralMesh::TetrahedralMesh(std::vector<Point<3>> nodes, std::vector<std::array<Index, 4>> tetrahedra,
                                 const std::string& source, std::vector<int> regions)
    : nodes_(std::move(nodes)), tetrahedra_(std::move(tetrahedra)), regions_(std::move(regions)) {
  if (tetrahedra_.empty()) throw InputError(fmt::format("{}: the solid has no tetrahedron", source));
  if (!regions_.empty() && regions_.size() != tetrahedra_.size())
    throw InputError(
        fmt::format("{}: {} regions for {} tetrahedra", source, regions_.size(), tetrahedra_.size()));
  if (const auto r = std::find_if(regions_.begin(), regions_.end(), [](int v) { return v < 0; });
      r != regions_.end())
    throw InputError(fmt::format("{}: tetrahedron {} is in region {}", source, r - regions_.begin(), *r));
  const auto n = static_cast<Index>(nodes_.size());
  for (Index i = 0; i < n; ++i)
    if (!nodes_[i].allFinite())
      throw InputError(fmt::format("{}: node {} of the solid's mesh is not finite", source, i));
  for (std::size_t k = 0; k < tetrahedra_.size(); ++k) {
    for (const Index v : tetrahedra_[k])
      if (v < 0 || v >= n)
        throw InputError(
            fmt::format("{}: tetrahedron {} names node {}, not one of the {} nodes", source, k, v, n));
    const Tetrahedron t = tetrahedron(static_cast<Index>(k));
    AlignedBox<3> bounds(t[0]);
    for (const Point<3>& v : t) bounds.extend(v);
    const double volume = tetrahedron_volume(t);
    if (!(volume > 1e-14 * bounds.volume()))
      throw InputError(
          fmt::format("{}: tetrahedron {} of the solid's mesh has no volume (vertices ({}), ({}), "
                      "({}), ({}))",
                      source, k, point_text(t[0]), point_text(t[1]), point_text(t[2]), point_text(t[3])));
    volume_ += volume;
    box_.extend(bounds);
  }
  // Buckets of about two tetrahedra's extent: a box of a few tetrahedra per bucket.
  const Point<3> size = box_.sizes();
  cell_ = 2.0 * std::cbrt(volume_ / static_cast<double>(tetrahedra_.size()));
  cell_ = std::max(cell_, size.maxCoeff() / 512.0);
  std::size_t buckets = 1;
  for (int c = 0; c < 3; ++c) {
    counts_[c] = std::max<Index>(1, static_cast<Index>(std::ceil(size[c] / cell_)));
    buckets *= static_cast<std::size_t>(counts_[c]);
  }
  const auto for_buckets = [&](std::size_t k, auto&& f) {
    const Tetrahedron t = tetrahedron(static_cast<Index>(k));
    AlignedBox<3> bounds(t[0]);
    for (const Point<3>& v : t) bounds.extend(v);
    const std::array<Index, 3> lo = cell_of(bounds.min()), hi = cell_of(bounds.max());
    for (Index z = lo[2]; z <= hi[2]; ++z)
      for (Index y = lo[1]; y <= hi[1]; ++y)
        for (Index x = lo[0]; x <= hi[0]; ++x)
          f((static_cast<std::size_t>(z) * counts_[1] + y) * counts_[0] + x);
  };
  start_.assign(buckets + 1, 0);
  for (std::size_t k = 0; k < tetrahedra_.size(); ++k)
    for_buckets(k, [&](std::size_t b) { ++start_[b + 1]; });
  for (std::size_t b = 0; b < buckets; ++b) start_[b + 1] += start_[b];
  bucket_.resize(static_cast<std::size_t>(start_.back()));
  std::vector<Index> fill(start_.begin(), start_.end() - 1);
  for (std::size_t k = 0; k < tetrahedra_.size(); ++k)
    for_buckets(k,
                [&](std::size_t b) { bucket_[static_cast<std::size_t>(fill[b]++)] = static_cast<Index>(k); });
}

Tetrahedron TetrahedralMesh::tetrahedron(Index k) const {
  const auto& t = tetrahedra_[static_cast<std::size_t>(k)];
  return {nodes_[t[0]], nodes_[t[1]], nodes_[t[2]], nodes_[t[3]]};
}

std::array<Index, 3> TetrahedralMesh::cell_of(const Point<3>& x) const {
  std::array<Index, 3> out;
  for (int c = 0; c < 3; ++c) {
    const double s = std::floor((x[c] - box_.min()[c]) / cell_);
    out[c] = static_cast<Index>(std::clamp(s, 0.0, static_cast<double>(counts_[c] - 1)));
  }
  return out;
}

Index TetrahedralMesh::locate(const Point<3>& x) const {
  const double slack = 1e-12 * box_.sizes().maxCoeff();
  if (!x.allFinite() || ((x - box_.min()).array() < -slack).any() || ((x - box_.max()).array() > slack).any())
    return -1;
  const std::array<Index, 3> c = cell_of(x);
  const std::size_t b = (static_cast<std::size_t>(c[2]) * counts_[1] + c[1]) * counts_[0] + c[0];
  for (Index i = start_[b]; i < start_[b + 1]; ++i) {
    const Index k = bucket_[static_cast<std::size_t>(i)];
    const Tetrahedron t = tetrahedron(k);
    Tensor2<3> edges;
    edges << t[1] - t[0], t[2] - t[0], t[3] - t[0];
    const Point<3> lambda = edges.inverse() * (x - t[0]);
    constexpr double tolerance = -1e-12;
    if (lambda.minCoeff() >= tolerance && 1.0 - lambda.sum() >= tolerance) return k;
  }
  return -1;
}

}  // namespace mfree
