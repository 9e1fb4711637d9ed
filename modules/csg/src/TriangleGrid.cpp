#include "TriangleGrid.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace reamsim::csg {

GridShape gridShape(const Bounds& domain, std::size_t faces, double targetPerCell, double surfaceArea, std::size_t maxCells) {
  const Vec3 size = !domain.empty() ? domain.max - domain.min : Vec3{1, 1, 1};
  const double ext[3] = {std::max(size.x, 1e-3), std::max(size.y, 1e-3), std::max(size.z, 1e-3)};
  const double volume = ext[0] * ext[1] * ext[2];
  GridShape g;
  if (surfaceArea > 0 && faces > 0) {
    // A cell of side c is crossed by about c² / (area per face) faces.
    g.cell = std::sqrt(targetPerCell * surfaceArea / double(faces));
  } else {
    // Without the area, sizing cells by the box volume gives roughly the wanted density on the occupied
    // cells for small bone-like shapes.
    g.cell = std::cbrt(volume / std::max(1.0, double(faces) / targetPerCell));
  }
  g.cell = std::max(g.cell, std::cbrt(volume / double(maxCells)));
  for (int i = 0; i < 3; ++i) g.cell = std::max(g.cell, ext[i] / 256.0);
  g.invCell = 1.0 / g.cell;
  for (int i = 0; i < 3; ++i) {
    g.n[i] = std::max(1, std::min(256, int(std::ceil(ext[i] / g.cell))));
    g.origin[i] = !domain.empty() ? domain.min[i] : 0.0;
  }
  return g;
}

void TriangleGrid::init(const Bounds& domain, std::size_t faces, double targetPerCell, double surfaceArea) {
  shape_ = gridShape(domain, faces, targetPerCell, surfaceArea, kMaxCells);
  cells_.assign(shape_.cellCount(), {});
  for (int i = 0; i < 3; ++i) nb_[i] = (shape_.n[i] + kBlock - 1) / kBlock;
  blockCount_.assign(std::size_t(nb_[0]) * nb_[1] * nb_[2], 0);
  boxes_.clear();
  loCell_.clear();
  present_.clear();
  stamp_.clear();
  epoch_ = 0;
}

template <class F, class KeepBlock>
void TriangleGrid::forCells(const Box3& b, F&& f, KeepBlock&& keepBlock) const {
  const auto lo = cellOf(b.lo), hi = cellOf(b.hi);
  if (lo == hi) {  // most queries: one cell
    f(index(lo[0], lo[1], lo[2]));
    return;
  }
  for (int bk = lo[2] / kBlock; bk <= hi[2] / kBlock; ++bk)
    for (int bj = lo[1] / kBlock; bj <= hi[1] / kBlock; ++bj)
      for (int bi = lo[0] / kBlock; bi <= hi[0] / kBlock; ++bi) {
        if (blockCount_[blockAt(bi, bj, bk)] == 0 || !keepBlock(bi, bj, bk)) continue;
        const int k1 = std::min(hi[2], bk * kBlock + kBlock - 1), j1 = std::min(hi[1], bj * kBlock + kBlock - 1),
                  i1 = std::min(hi[0], bi * kBlock + kBlock - 1);
        for (int k = std::max(lo[2], bk * kBlock); k <= k1; ++k)
          for (int j = std::max(lo[1], bj * kBlock); j <= j1; ++j)
            for (int i = std::max(lo[0], bi * kBlock); i <= i1; ++i) f(index(i, j, k));
      }
}

template <class F>
void TriangleGrid::forEveryCell(const Box3& b, F&& f) const {
  const auto lo = cellOf(b.lo), hi = cellOf(b.hi);
  for (int k = lo[2]; k <= hi[2]; ++k)
    for (int j = lo[1]; j <= hi[1]; ++j)
      for (int i = lo[0]; i <= hi[0]; ++i) f(index(i, j, k), blockAt(i / kBlock, j / kBlock, k / kBlock));
}

void TriangleGrid::insert(std::uint32_t slot, const Box3& box) {
  if (slot >= boxes_.size()) {
    boxes_.resize(slot + 1);
    loCell_.resize(slot + 1);
    present_.resize(slot + 1, 0);
    stamp_.resize(slot + 1, 0);
  }
  if (present_[slot]) remove(slot);
  boxes_[slot] = box;
  const auto lo = cellOf(box.lo);
  loCell_[slot] = {std::uint8_t(lo[0]), std::uint8_t(lo[1]), std::uint8_t(lo[2])};
  present_[slot] = 1;
  forEveryCell(box, [&](std::size_t c, std::size_t block) {
    cells_[c].push_back(slot);
    ++blockCount_[block];
  });
}

void TriangleGrid::remove(std::uint32_t slot) {
  if (!contains(slot)) return;
  forEveryCell(boxes_[slot], [&](std::size_t c, std::size_t block) {
    auto& v = cells_[c];
    auto it = std::find(v.begin(), v.end(), slot);
    if (it != v.end()) {
      *it = v.back();
      v.pop_back();
      --blockCount_[block];
    }
  });
  present_[slot] = 0;
}

void TriangleGrid::beginQuery(std::vector<std::uint32_t>& out) {
  out.clear();
  if (++epoch_ == 0) {  // wrapped: forget old stamps
    std::fill(stamp_.begin(), stamp_.end(), 0);
    epoch_ = 1;
  }
}

bool TriangleGrid::mark(std::uint32_t slot) {
  if (stamp_[slot] == epoch_) return false;
  stamp_[slot] = epoch_;
  return true;
}

void TriangleGrid::query(const Box3& q, std::vector<std::uint32_t>& out) {
  // Within one cell (a point's query: the clean-up's vertex stars) each slot is listed once: no stamps.
  const bool oneCell = cellOf(q.lo) == cellOf(q.hi);
  beginQuery(out);
  forCells(q, [&](std::size_t c) {
    for (std::uint32_t s : cells_[c])
      if ((oneCell || mark(s)) && boxes_[s].overlaps(q)) out.push_back(s);
  });
}

void TriangleGrid::query(const Box3& q, const std::function<bool(const Box3&)>& mayHold,
                         std::vector<std::uint32_t>& out) {
  beginQuery(out);
  // Block boxes padded by a millionth of a cell: a point on a cell's face may be filed in either cell.
  const double pad = 1e-6 * shape_.cell, side = kBlock * shape_.cell;
  auto keepBlock = [&](int bi, int bj, int bk) {
    const int b[3] = {bi, bj, bk};
    Box3 box;
    for (int a = 0; a < 3; ++a) {
      if (b[a] == 0 || (b[a] + 1) * kBlock >= shape_.n[a]) return true;  // border: holds faces beyond the domain
      box.lo[a] = shape_.origin[a] + b[a] * side - pad;
      box.hi[a] = shape_.origin[a] + (b[a] + 1) * side + pad;
    }
    return mayHold(box);
  };
  forCells(
      q,
      [&](std::size_t c) {
        for (std::uint32_t s : cells_[c])
          if (mark(s) && boxes_[s].overlaps(q)) out.push_back(s);
      },
      keepBlock);
}

void TriangleGrid::queryShared(const Box3& q, std::vector<std::uint32_t>& out) const {
  out.clear();
  const auto qlo = cellOf(q.lo);
  const bool oneCell = qlo == cellOf(q.hi);  // most queries: nothing to deduplicate
  forCells(q, [&](std::size_t c) {
    for (std::uint32_t s : cells_[c]) {
      if (!boxes_[s].overlaps(q)) continue;
      if (oneCell) {
        out.push_back(s);
        continue;
      }
      if (shape_.firstSharedCell(loCell_[s], qlo) == c) out.push_back(s);
    }
  });
}

}  // namespace reamsim::csg
