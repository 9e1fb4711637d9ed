#include "PackedTriangleGrid.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace reamsim::csg {

void PackedTriangleGrid::build(const Bounds& domain, std::vector<Box3> boxes, double targetPerCell) {
  shape_ = gridShape(domain, boxes.size(), targetPerCell, 0, TriangleGrid::kMaxCells);
  boxes_ = std::move(boxes);
  loCell_.resize(boxes_.size());
  std::vector<std::array<int, 3>> hiCell(boxes_.size());
  cellStart_.assign(shape_.cellCount() + 1, 0);
  // Two passes: count each cell's slots, then file them behind the prefix sums.
  auto forCellsOf = [&](std::size_t s, auto&& f) {
    const auto &lo = loCell_[s], &hi = hiCell[s];
    for (int k = lo[2]; k <= hi[2]; ++k)
      for (int j = lo[1]; j <= hi[1]; ++j)
        for (int i = lo[0]; i <= hi[0]; ++i) f(shape_.index(i, j, k));
  };
  for (std::size_t s = 0; s < boxes_.size(); ++s) {
    loCell_[s] = shape_.cellOf(boxes_[s].lo);
    hiCell[s] = shape_.cellOf(boxes_[s].hi);
    forCellsOf(s, [&](std::size_t c) { ++cellStart_[c + 1]; });
  }
  for (std::size_t c = 1; c < cellStart_.size(); ++c) cellStart_[c] += cellStart_[c - 1];
  slots_.resize(cellStart_.back());
  std::vector<std::uint32_t> fill(cellStart_.begin(), cellStart_.end() - 1);
  for (std::size_t s = 0; s < boxes_.size(); ++s)
    forCellsOf(s, [&](std::size_t c) { slots_[fill[c]++] = std::uint32_t(s); });
}

void PackedTriangleGrid::build(std::vector<Box3> boxes, double targetPerCell) {
  Bounds domain;
  for (const Box3& b : boxes) domain.add(b.bounds());
  build(domain, std::move(boxes), targetPerCell);
}

void PackedTriangleGrid::query(const Box3& q, std::vector<std::uint32_t>& out) const {
  out.clear();
  if (boxes_.empty()) return;
  const auto lo = shape_.cellOf(q.lo), hi = shape_.cellOf(q.hi);
  for (int k = lo[2]; k <= hi[2]; ++k)
    for (int j = lo[1]; j <= hi[1]; ++j)
      for (int i = lo[0]; i <= hi[0]; ++i) {
        const std::size_t c = shape_.index(i, j, k);
        for (std::uint32_t e = cellStart_[c]; e < cellStart_[c + 1]; ++e) {
          const std::uint32_t s = slots_[e];
          if (!boxes_[s].overlaps(q)) continue;
          if (shape_.firstSharedCell(loCell_[s], lo) == c) out.push_back(s);
        }
      }
}

void PackedTriangleGrid::ray(const std::array<double, 3>& origin, int axis, int dir,
                             std::vector<std::uint32_t>& out) const {
  // The ray as a degenerate box reaching to infinity: boxes beyond the domain sit in the border cells.
  Box3 q{origin, origin};
  if (dir > 0)
    q.hi[axis] = std::numeric_limits<double>::infinity();
  else
    q.lo[axis] = -std::numeric_limits<double>::infinity();
  query(q, out);
}

}  // namespace reamsim::csg
