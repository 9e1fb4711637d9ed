#pragma once
// A uniform grid built once over a fixed list of triangle boxes, its cells packed in one array (a count
// per cell, then the slots): no allocation per cell. The tool's faces are filed afresh for every cut, and
// TriangleGrid, which supports insert and remove, spent most of that on growing its cells' vectors (~0.35 ms
// for the glenoid reamer, time the cut waited for on a small bone). Same cell sizing and the same shared
// query as TriangleGrid: boxes are closed and conservative, each slot is reported once.
#include <array>
#include <cstdint>
#include <vector>

#include "TriangleGrid.h"

namespace reamsim::csg {

class PackedTriangleGrid {
 public:
  // Slot i has box boxes[i]; `domain` should hold them (boxes beyond it are filed in the border cells).
  void build(const Bounds& domain, std::vector<Box3> boxes, double targetPerCell);
  // The same over the boxes' own union.
  void build(std::vector<Box3> boxes, double targetPerCell);
  const Box3& box(std::uint32_t slot) const { return boxes_[slot]; }
  // Slots whose boxes overlap `query`, each once, in no particular order (const: threads may share it).
  void query(const Box3& query, std::vector<std::uint32_t>& out) const;
  // Slots whose boxes an axis-parallel ray from `origin` along +axis (dir > 0) or −axis meets.
  void ray(const std::array<double, 3>& origin, int axis, int dir, std::vector<std::uint32_t>& out) const;

 private:
  GridShape shape_;
  std::vector<std::uint32_t> cellStart_;  // cell c holds slots_[cellStart_[c] .. cellStart_[c + 1])
  std::vector<std::uint32_t> slots_;
  std::vector<Box3> boxes_;
  std::vector<std::array<int, 3>> loCell_;  // each slot's first cell: a slot is reported from the first cell
                                            // its box shares with the query's range
};

}  // namespace reamsim::csg
