// Connected bone regions on the voxel grid (6-connectivity), chosen before isosurfacing: cheaper than
// labelling a million-triangle surface, and it lets enclosed cavities be filled. Removing a region never
// moves the kept surface: a removed voxel has no grid edge to a kept one (they would be connected).
// Labelling works on runs of voxels along i joined by union-find (a few hundred thousand runs instead of
// millions of voxels).
#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "Stages.h"

namespace reamsim::ct::detail {
namespace {

struct Run {
  int i0, i1;  // inclusive range along i
};

class RunLabels {
 public:
  // Runs of voxels with `member(value)` in every row (j, k), joined across rows j±1 and k±1 when they
  // overlap along i.
  template <class Member>
  RunLabels(const PaddedField& f, Member&& member) : d_(f.dims) {
    const std::size_t rows = std::size_t(d_[1]) * d_[2];
    rowStart_.assign(rows + 1, 0);
    for (std::size_t r = 0; r < rows; ++r) {
      const float* row = &f.values[r * std::size_t(d_[0])];
      int i = 0;
      while (i < d_[0]) {
        while (i < d_[0] && !member(row[i])) ++i;
        if (i == d_[0]) break;
        const int start = i;
        while (i < d_[0] && member(row[i])) ++i;
        runs_.push_back({start, i - 1});
      }
      rowStart_[r + 1] = std::uint32_t(runs_.size());
    }
    parent_.resize(runs_.size());
    std::iota(parent_.begin(), parent_.end(), 0u);
    for (int k = 0; k < d_[2]; ++k)
      for (int j = 0; j < d_[1]; ++j) {
        const std::size_t r = row(j, k);
        if (j > 0) joinRows(r, row(j - 1, k));
        if (k > 0) joinRows(r, row(j, k - 1));
      }
  }

  std::size_t row(int j, int k) const { return std::size_t(k) * d_[1] + j; }
  std::uint32_t root(std::uint32_t x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  std::size_t runCount() const { return runs_.size(); }
  const Run& run(std::size_t r) const { return runs_[r]; }
  std::uint32_t rowBegin(std::size_t row) const { return rowStart_[row]; }
  std::uint32_t rowEnd(std::size_t row) const { return rowStart_[row + 1]; }

 private:
  void join(std::uint32_t a, std::uint32_t b) {
    a = root(a);
    b = root(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }
  void joinRows(std::size_t ra, std::size_t rb) {
    std::uint32_t a = rowStart_[ra], b = rowStart_[rb];
    const std::uint32_t ae = rowStart_[ra + 1], be = rowStart_[rb + 1];
    while (a < ae && b < be) {
      if (runs_[a].i1 >= runs_[b].i0 && runs_[b].i1 >= runs_[a].i0) join(a, b);
      if (runs_[a].i1 < runs_[b].i1) ++a;
      else ++b;
    }
  }

  std::array<int, 3> d_;
  std::vector<Run> runs_;
  std::vector<std::uint32_t> rowStart_, parent_;
};

}  // namespace

RegionStats keepRegions(PaddedField& field, ComponentMode mode, const std::optional<std::array<int, 3>>& seed,
                        bool fillCavities, const Tick& tick) {
  RegionStats stats;
  const std::array<int, 3>& d = field.dims;
  std::vector<float>& f = field.values;
  const auto forRun = [&](std::size_t row, const Run& run, auto&& fn) {
    float* p = &f[row * std::size_t(d[0])];
    for (int i = run.i0; i <= run.i1; ++i) fn(p[i]);
  };

  RunLabels inside(field, [](float v) { return v > 0; });
  if (tick) tick(0.3);
  std::vector<std::size_t> size(inside.runCount(), 0);
  std::vector<std::uint32_t> rowOfRun(inside.runCount());
  for (std::size_t r = 0; r < std::size_t(d[1]) * d[2]; ++r)
    for (std::uint32_t x = inside.rowBegin(r); x < inside.rowEnd(r); ++x) {
      rowOfRun[x] = std::uint32_t(r);
      size[inside.root(x)] += std::size_t(inside.run(x).i1 - inside.run(x).i0 + 1);
    }
  for (std::size_t x = 0; x < size.size(); ++x)
    if (size[x] > 0) {
      ++stats.regions;
      stats.inRange += size[x];
    }
  if (stats.regions == 0) throw std::runtime_error("no voxel lies within the threshold range");

  // The root(s) to keep.
  std::uint32_t chosen = 0;
  if (mode == ComponentMode::Largest) {
    chosen = std::uint32_t(std::max_element(size.begin(), size.end()) - size.begin());
  } else if (mode == ComponentMode::Seed) {
    if (!seed) throw std::invalid_argument("component mode 'seed' needs a seed point");
    // The region containing the seed voxel, or the nearest one within 3 voxels.
    double best = HUGE_VAL;
    bool found = false;
    for (int dk = -3; dk <= 3; ++dk)
      for (int dj = -3; dj <= 3; ++dj) {
        const int j = (*seed)[1] + dj, k = (*seed)[2] + dk;
        if (j < 0 || k < 0 || j >= d[1] || k >= d[2]) continue;
        const std::size_t r = inside.row(j, k);
        for (std::uint32_t x = inside.rowBegin(r); x < inside.rowEnd(r); ++x) {
          const Run& run = inside.run(x);
          const int di = std::clamp((*seed)[0], run.i0, run.i1) - (*seed)[0];
          if (std::abs(di) > 3) continue;
          const double dist = di * di + dj * dj + dk * dk;
          if (dist < best) {
            best = dist;
            chosen = inside.root(x);
            found = true;
          }
        }
      }
    if (!found) throw std::invalid_argument("the seed point is not within 3 voxels of bone in the threshold range");
  }
  for (std::uint32_t x = 0; x < inside.runCount(); ++x) {
    const bool keep = mode == ComponentMode::All || inside.root(x) == chosen;
    const std::size_t len = std::size_t(inside.run(x).i1 - inside.run(x).i0 + 1);
    if (keep) stats.kept += len;
    else forRun(rowOfRun[x], inside.run(x), [](float& v) { v = -v; });  // removed region: background now
  }
  if (tick) tick(0.6);

  // Cavities: background runs not connected to the border layer (which is all background).
  if (fillCavities) {
    RunLabels outside(field, [](float v) { return v <= 0; });
    std::vector<std::uint8_t> exterior(outside.runCount(), 0);
    for (int k = 0; k < d[2]; ++k)
      for (int j = 0; j < d[1]; ++j) {
        const bool borderRow = j == 0 || k == 0 || j == d[1] - 1 || k == d[2] - 1;
        const std::size_t r = outside.row(j, k);
        for (std::uint32_t x = outside.rowBegin(r); x < outside.rowEnd(r); ++x)
          if (borderRow || outside.run(x).i0 == 0 || outside.run(x).i1 == d[0] - 1) exterior[outside.root(x)] = 1;
      }
    for (int k = 0; k < d[2]; ++k)
      for (int j = 0; j < d[1]; ++j) {
        const std::size_t r = outside.row(j, k);
        for (std::uint32_t x = outside.rowBegin(r); x < outside.rowEnd(r); ++x) {
          if (exterior[outside.root(x)]) continue;
          forRun(r, outside.run(x), [](float& v) { v = std::max(-v, 1e-3f); });
          stats.cavities += std::size_t(outside.run(x).i1 - outside.run(x).i0 + 1);
        }
      }
  }
  // Bone on the faces of the original volume (padded index 1 and dims-2).
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const int fixed = side == 0 ? 1 : d[std::size_t(axis)] - 2;
      const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
      bool any = false;
      for (int u = 1; u < d[std::size_t(a2)] - 1 && !any; ++u)
        for (int t = 1; t < d[std::size_t(a1)] - 1 && !any; ++t) {
          std::array<int, 3> p{};
          p[std::size_t(axis)] = fixed;
          p[std::size_t(a1)] = t;
          p[std::size_t(a2)] = u;
          any = f[field.index(p[0], p[1], p[2])] > 0;
        }
      stats.touches[std::size_t(2 * axis + side)] = any;
    }
  if (tick) tick(1.0);
  return stats;
}

}  // namespace reamsim::ct::detail
