#pragma once
// Uniform grid over triangle boxes: which bone faces may touch a tool, in time proportional to the
// cells the tool's box covers. Boxes are closed and conservative (they contain the exact triangle), so
// a face whose box misses the query box cannot touch anything inside it. Coordinates outside the
// domain are clamped to the border cells, so faces created outside it are still found.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

#include "reamsim/mesh/Bounds.h"

namespace reamsim::csg {

struct Box3 {
  std::array<double, 3> lo{}, hi{};
  // The empty box (lo = +inf, hi = -inf), which add() grows.
  static Box3 empty() {
    constexpr double inf = std::numeric_limits<double>::infinity();
    return {{inf, inf, inf}, {-inf, -inf, -inf}};
  }
  void add(const Vec3& p) {
    for (int i = 0; i < 3; ++i) {
      lo[i] = std::min(lo[i], p[i]);
      hi[i] = std::max(hi[i], p[i]);
    }
  }
  Bounds bounds() const {
    Bounds b;
    b.add(Vec3{lo[0], lo[1], lo[2]});
    b.add(Vec3{hi[0], hi[1], hi[2]});
    return b;
  }
  bool overlaps(const Box3& o) const {
    for (int i = 0; i < 3; ++i)
      if (hi[i] < o.lo[i] || o.hi[i] < lo[i]) return false;
    return true;
  }
};

// The cells of a uniform grid over `domain`: about `targetPerCell` faces per occupied cell for a surface of
// `faces` faces (sized by `surfaceArea` when given, else by the box's volume), at most 256 cells along an
// axis and `maxCells` in all. Both grids (TriangleGrid, PackedTriangleGrid) index their cells through it.
struct GridShape {
  std::array<double, 3> origin{};
  double cell = 1;
  double invCell = 1;  // cellOf multiplies (a division per axis showed in profiles); still monotone
  std::array<int, 3> n{1, 1, 1};

  // The cell holding p, clamped to the grid: points beyond the domain (and NaN) fall in the border cells.
  std::array<int, 3> cellOf(const std::array<double, 3>& p) const {
    std::array<int, 3> c{};
    for (int i = 0; i < 3; ++i) {
      const double f = std::floor((p[i] - origin[i]) * invCell);
      c[i] = !(f >= 0) ? 0 : (f >= n[i] ? n[i] - 1 : int(f));
    }
    return c;
  }
  std::size_t index(int i, int j, int k) const { return (std::size_t(k) * n[1] + j) * n[0] + i; }
  std::size_t cellCount() const { return std::size_t(n[0]) * n[1] * n[2]; }
  // The first cell a slot's cell range (from slotLo) shares with a query's (from queryLo): cellOf is
  // monotone, so it is the larger of their first cells. A query reports the slot from that cell only, so
  // each once, without stamps (threads may share the grid).
  template <class Coord>
  std::size_t firstSharedCell(const std::array<Coord, 3>& slotLo, const std::array<int, 3>& queryLo) const {
    return index(std::max(int(slotLo[0]), queryLo[0]), std::max(int(slotLo[1]), queryLo[1]),
                 std::max(int(slotLo[2]), queryLo[2]));
  }
};
GridShape gridShape(const Bounds& domain, std::size_t faces, double targetPerCell, double surfaceArea, std::size_t maxCells);

class TriangleGrid {
 public:
  // About `targetPerCell` faces per occupied cell for a surface of `faces` faces spanning `domain`. With the
  // surface's area the cells follow the faces' size (a surface fills its box sparsely, and a bone's faces
  // are much smaller than its box divided by their count), within kMaxCells.
  void init(const Bounds& domain, std::size_t faces, double targetPerCell = 8.0, double surfaceArea = 0);
  static constexpr std::size_t kMaxCells = std::size_t(1) << 21;
  void insert(std::uint32_t slot, const Box3& box);
  void remove(std::uint32_t slot);  // no-op for a slot that is not in the grid
  const Box3& box(std::uint32_t slot) const { return boxes_[slot]; }
  bool contains(std::uint32_t slot) const { return slot < present_.size() && present_[slot] != 0; }

  // Slots whose boxes overlap `query`, each once, in no particular order.
  void query(const Box3& query, std::vector<std::uint32_t>& out);
  // The same, skipping the blocks of cells for which `mayHold(blockBox)` is false: a face all of whose
  // cells are skipped is not reported. Border blocks (which also hold faces beyond the domain) are never
  // skipped.
  void query(const Box3& query, const std::function<bool(const Box3&)>& mayHold, std::vector<std::uint32_t>& out);
  // The slots filed in the cell that holds p: every slot whose box holds p, and others (each once). A
  // superset, read without the boxes, for a caller that tests its own condition on each (the clean-up's
  // vertex stars: the faces with a given corner).
  const std::vector<std::uint32_t>& slotsInCellOf(const Vec3& p) const {
    const auto c = cellOf({p.x, p.y, p.z});
    return cells_[index(c[0], c[1], c[2])];
  }
  // Slots whose boxes overlap `query`, each once, in no particular order; const, so threads may share the
  // grid: a slot is reported only from the first cell of its box's range within the query's (no stamps).
  void queryShared(const Box3& query, std::vector<std::uint32_t>& out) const;

 private:
  std::array<int, 3> cellOf(const std::array<double, 3>& p) const { return shape_.cellOf(p); }
  // A slot's first cell (its box's lo corner), kept so that shared queries need no cellOf per face found.
  using CellCoords = std::array<std::uint8_t, 3>;  // shape_.n <= 256 along every axis
  std::size_t index(int i, int j, int k) const { return shape_.index(i, j, k); }
  // Cells are grouped in blocks of kBlock³ that count the entries of their cells, so that queries skip
  // empty space a block at a time (a tool's box at 400k faces spans ~10⁵ cells, most of them empty).
  static constexpr int kBlock = 4;
  std::size_t blockAt(int bi, int bj, int bk) const { return (std::size_t(bk) * nb_[1] + bj) * nb_[0] + bi; }
  // f(cellIndex, blockIndex) for every cell of b's range (insert and remove: empty blocks too).
  template <class F>
  void forEveryCell(const Box3& b, F&& f) const;
  // f(cellIndex) for the cells of b's range in non-empty blocks for which keepBlock(bi, bj, bk) holds.
  template <class F, class KeepBlock>
  void forCells(const Box3& b, F&& f, KeepBlock&& keepBlock) const;
  template <class F>
  void forCells(const Box3& b, F&& f) const {
    forCells(b, f, [](int, int, int) { return true; });
  }
  void beginQuery(std::vector<std::uint32_t>& out);  // clears out; a new stamp for mark()
  bool mark(std::uint32_t slot);  // true the first time a slot is seen in the current query

  GridShape shape_;
  std::array<int, 3> nb_{1, 1, 1};
  std::vector<std::vector<std::uint32_t>> cells_;
  std::vector<std::uint32_t> blockCount_;  // entries in the cells of each block
  std::vector<Box3> boxes_;
  std::vector<CellCoords> loCell_;
  std::vector<std::uint8_t> present_;
  std::vector<std::uint32_t> stamp_;
  std::uint32_t epoch_ = 0;
};

}  // namespace reamsim::csg
