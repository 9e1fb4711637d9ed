#pragma once
// Bounding-volume hierarchy (binary, axis-aligned boxes, binned-SAH build) over triangle *slots*, with
// local updates so that it follows a bone being cut without a full rebuild.
//
// Slots are the caller's stable triangle ids (BoneState triangle slots, or mesh indices). The tree keeps
// its own copy of each triangle's corners, so queries never touch the BoneState and an update only needs
// the slots that changed. update():
//   1. removes slots from their leaves, then one pass over the dirty paths settles sizes, frees emptied
//      leaves and subtrees (a node left with one child is replaced by it) and refits their boxes;
//   2. builds one SAH subtree over the new slots (a cut adds its triangles in one place) and grafts it
//      where the surface-area cost grows least (a subtree spanning separate clusters is split first);
//   3. refits the graft's path;
//   4. keeps quality: every node counts the triangles inserted/removed below it since that subtree was
//      last built; on the paths this update touched, a subtree whose count exceeds half its size is
//      rebuilt (binned SAH) — the smallest such subtrees first, paid from a rebuild credit proportional to
//      the edits, so an update costs O(edits log n) amortised. See docs/COLLISION.md.
// Boxes are padded (kBoxPadRelative x the triangle's extent + an absolute term) so that the Moeller-Trumbore
// barycentric slack and rounding never let a query miss a triangle that the brute force would report.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "reamsim/core/HugePageAllocator.h"
#include "reamsim/mesh/Bounds.h"
#include "reamsim/mesh/TriangleMesh.h"
#include "reamsim/mesh/Vec3.h"

namespace reamsim {

struct BvhTriangle {
  Vec3 a, b, c;
};

// One node, 64 bytes. Internal: `left`/`right` are child node indices. Leaf: right == -1, `left` is where
// its block of slots starts (leafSlots: kBuildLeafSize or kLeafCapacity entries), `count` the number used.
struct BvhNode {
  Vec3 lo, hi;
  std::int32_t parent = -1;
  std::int32_t left = -1;
  std::int32_t right = -1;
  std::int32_t count = 0;
  bool isLeaf() const { return right < 0; }
};

// A slab beside each node's box: its triangles lie (padded like the boxes) between two planes normal to
// `axis`, the node's area-weighted triangle normal. A patch of surface is thin along its own normal however
// it is tilted against x, y and z, where its box is as thick as it is wide; queries bound a node by the
// box and the slab together. `normalSum` (the unnormalised area-weighted normal) gives a parent its axis.
struct BvhSlab {
  Vec3 axis{0, 0, 1};
  double lo = 0, hi = 0;
  Vec3 normalSum;
};

// Range of u.x over the region box [lo, hi] ∩ slab, conservatively (padded for rounding): u = a n + w with
// w normal to the slab's axis n, so u.x lies within a [slab.lo, slab.hi] + the box's range of w.x; the
// box's own range of u.x also holds, and the tighter of the two is returned. Inline, with the box's middle
// and half-extent kept, because a search ranges each node it meets along several axes.
struct BoxSlabRegion {
  Vec3 c, h;  // the box's middle and half-extent
  const BvhSlab& slab;
  BoxSlabRegion(const Vec3& lo, const Vec3& hi, const BvhSlab& s) : c((lo + hi) * 0.5), h((hi - lo) * 0.5), slab(s) {}
  void range(const Vec3& u, double& outLo, double& outHi) const {
    const double uc = dot(u, c);
    const double uh = std::abs(u.x) * h.x + std::abs(u.y) * h.y + std::abs(u.z) * h.z;
    const double a = dot(u, slab.axis);
    const Vec3 w = u - slab.axis * a;
    const double wc = dot(w, c), wh = std::abs(w.x) * h.x + std::abs(w.y) * h.y + std::abs(w.z) * h.z;
    const double slo = a >= 0 ? a * slab.lo : a * slab.hi, shi = a >= 0 ? a * slab.hi : a * slab.lo;
    // Rounding of the products and sums above: relative to the magnitudes involved.
    const double pad = 1e-12 * (std::abs(uc) + std::abs(slab.lo) + std::abs(slab.hi) + h.x + h.y + h.z) + 1e-300;
    outLo = std::max(uc - uh, slo + (wc - wh)) - pad;
    outHi = std::min(uc + uh, shi + (wc + wh)) + pad;
  }
  // The same along the unit direction u from point p to the box's middle (false, nothing set, when p is
  // that middle). A patch seen from a point off its own normal is thin along that line too, where its box
  // is not: |x - p| >= u . (x - p) bounds the distance from p, and a ball about p is ranged along u as an
  // interval.
  bool rangeFrom(const Vec3& p, Vec3& u, double& outLo, double& outHi) const {
    u = c - p;
    const double len = norm(u);
    if (!(len > 0)) return false;
    u = u / len;
    range(u, outLo, outHi);
    return true;
  }
};
inline void regionRange(const Vec3& lo, const Vec3& hi, const BvhSlab& slab, const Vec3& u, double& outLo, double& outHi) {
  BoxSlabRegion(lo, hi, slab).range(u, outLo, outHi);
}

struct BvhUpdateStats {
  std::size_t removed = 0;
  std::size_t added = 0;
  std::size_t leafSplits = 0;
  std::size_t rebuiltSubtrees = 0;
  std::size_t rebuiltTriangles = 0;  // triangles re-sorted by subtree rebuilds in this update
  std::size_t refitNodes = 0;
  bool fullRebuild = false;
  double milliseconds = 0;
};

// Surface-area-heuristic cost (traversal cost 1, triangle test cost 1, normalised by the root box area):
// the expected number of box and triangle tests of a random ray. Lower is better.
struct BvhQuality {
  double sahCost = 0;
  std::size_t nodes = 0;
  std::size_t leaves = 0;
  std::size_t triangles = 0;
  std::size_t maxDepth = 0;
  double meanLeafSize = 0;
};

class TriangleBvh {
 public:
  static constexpr int kLeafCapacity = 8;   // the most slots a leaf holds (a build makes leaves this large
                                            // only where the SAH finds splitting them dearer)
  static constexpr int kBuildLeafSize = 4;  // leaves made by a build hold at most this many
  static constexpr double kBoxPadRelative = 1e-7;
  static constexpr double kRebuildFraction = 0.5;  // rebuild a subtree once edits exceed this share of it

  TriangleBvh() = default;
  // Slot i = triangle i. Throws std::invalid_argument for an out-of-range vertex index.
  static TriangleBvh fromMesh(const TriangleMesh& mesh);
  // Slots given explicitly (slots.size() == triangles.size(), distinct).
  static TriangleBvh fromTriangles(const std::vector<std::uint32_t>& slots, const std::vector<BvhTriangle>& triangles);

  // Local update. Removed slots must be in the tree; added slots must not be (after the removals), so a
  // slot may be removed and re-added in the same call. Throws std::invalid_argument otherwise (the tree is
  // then unchanged).
  BvhUpdateStats update(const std::vector<std::uint32_t>& removedSlots, const std::vector<std::uint32_t>& addedSlots,
                        const std::vector<BvhTriangle>& addedTriangles);
  void rebuild();  // full rebuild from the current triangles
  // Rebuild work the quality maintenance may spend per edited triangle, amortised (default 1; 0 = refit
  // and graft only, e.g. inside a haptic frame, with maintenance left to a later update).
  void setRebuildCreditPerEdit(double credit) { rebuildCreditPerEdit_ = credit; }

  // --- read access for the queries ---
  bool empty() const { return root_ < 0; }
  // Changes whenever the triangles do (build, rebuild, update), and is never shared by two trees built or
  // edited apart: what a query cache keyed on this tree (FaceDistanceTracker) checks before trusting itself.
  std::uint64_t revision() const { return revision_; }
  std::int32_t root() const { return root_; }
  const HugePageVector<BvhNode>& nodes() const { return nodes_; }
  const BvhSlab& slab(std::int32_t node) const { return slabs_[std::size_t(node)]; }
  // A cache hint for a search about to read a node (and its slab): on a large tree these reads miss the
  // cache, and issuing both children's at once lets the misses overlap. No effect on results.
  void prefetchNode(std::int32_t node, bool withSlab) const {
    __builtin_prefetch(&nodes_[std::size_t(node)]);
    if (withSlab) __builtin_prefetch(&slabs_[std::size_t(node)]);
  }
  const std::uint32_t* leafSlots(const BvhNode& leaf) const { return &blocks_[std::size_t(leaf.left)]; }
  // A leaf's triangles side by side, in the order of leafSlots (a copy the tree keeps: by slot they lie
  // scattered in the mesh's face order, one or two cache misses each on a large bone).
  const BvhTriangle* leafTriangles(const BvhNode& leaf) const { return &leafTris_[std::size_t(leaf.left)]; }
  // Positions: leaf entries as one index (leafPosition(leaf) + i is the leaf's i-th), for searches that queue
  // a bone triangle and read it again later; valid until the tree changes.
  static std::uint32_t leafPosition(const BvhNode& leaf) { return std::uint32_t(leaf.left); }
  std::uint32_t slotAt(std::uint32_t position) const { return blocks_[position]; }
  const BvhTriangle& triangleAt(std::uint32_t position) const { return leafTris_[position]; }
  bool contains(std::uint32_t slot) const { return slot < leafOf_.size() && leafOf_[slot] >= 0; }
  const BvhTriangle& triangle(std::uint32_t slot) const { return tris_[slot]; }
  std::size_t triangleCount() const { return triangleCount_; }
  std::size_t slotCapacity() const { return tris_.size(); }  // 1 + largest slot ever stored
  Bounds bounds() const;
  // Calls f(slot) for every triangle in the subtree of `node`.
  template <class F>
  void forEachSlot(std::int32_t node, F&& f) const;

  BvhQuality quality() const;  // O(nodes)
  // Bytes of the node, slab and triangle arrays the system backs with huge pages (a report: 0 where it has
  // none to give; reads /proc/self/smaps).
  std::size_t hugePageBytes() const;
  // Structural self-check for tests: parent links, boxes enclose children and padded triangles, counts,
  // slot -> leaf map. Returns an empty string when consistent, else the first problem found.
  std::string validate() const;

  // Triangle box with the padding described above (what leaves enclose).
  static void paddedBox(const BvhTriangle& t, Vec3& lo, Vec3& hi) {  // inline: queries box every triangle they reach
    lo = {std::min({t.a.x, t.b.x, t.c.x}), std::min({t.a.y, t.b.y, t.c.y}), std::min({t.a.z, t.b.z, t.c.z})};
    hi = {std::max({t.a.x, t.b.x, t.c.x}), std::max({t.a.y, t.b.y, t.c.y}), std::max({t.a.z, t.b.z, t.c.z})};
    const Vec3 d = hi - lo;
    const double mag = std::max({std::abs(lo.x), std::abs(lo.y), std::abs(lo.z), std::abs(hi.x), std::abs(hi.y),
                                 std::abs(hi.z)});
    const double pad = kBoxPadRelative * (d.x + d.y + d.z) + 1e-12 * (1 + mag);
    lo -= Vec3{pad, pad, pad};
    hi += Vec3{pad, pad, pad};
  }

 private:
  struct BuildRef;
  std::int32_t buildSubtree(std::vector<BuildRef>& refs, std::size_t begin, std::size_t end, std::int32_t parent);
  std::int32_t buildRange(std::vector<BuildRef>& refs, std::size_t begin, std::size_t end, std::int32_t parent,
                          const Vec3& lo, const Vec3& hi, const Vec3& clo, const Vec3& chi);
  BuildRef refOf(std::uint32_t slot) const;  // the triangle's padded box, centroid and slot
  std::vector<BuildRef> refsOf(const std::vector<std::uint32_t>& slots) const;
  std::int32_t makeLeaf(const BuildRef* refs, std::size_t n, std::int32_t parent);
  // Completes a built internal node: its children, its box, its subtree size and its slab.
  void setChildren(std::int32_t node, std::int32_t left, std::int32_t right, const Vec3& lo, const Vec3& hi,
                   std::size_t size);
  std::int32_t buildMorton(std::vector<BuildRef>& refs, std::int32_t parent);
  std::int32_t mortonRange(const BuildRef* refs, const std::uint32_t* codes, std::size_t n, std::int32_t parent);
  std::int32_t allocNode();
  void layOutInPairBlocks();
  std::int32_t allocBlock(std::size_t entries);
  void freeBlock(std::int32_t start);
  void freeSubtree(std::int32_t node, std::vector<std::uint32_t>* slotsOut);
  void replaceChild(std::int32_t parent, std::int32_t oldChild, std::int32_t newChild);
  void removeSlot(std::uint32_t slot);
  void closeLeafHoles(const BvhNode& leaf, int entries);
  static constexpr std::uint32_t kRemovedEntry = 0xFFFFFFFFu;  // a hole in a leaf block during an update
  std::int32_t settle(std::int32_t node, std::int32_t& removedBelow, BvhUpdateStats& stats);
  void touch(std::int32_t node);
  std::int32_t bestSibling(const Vec3& lo, const Vec3& hi) const;
  void graft(std::int32_t subtree, BvhUpdateStats& stats);
  std::int32_t rebuildSubtree(std::int32_t node, const std::vector<std::uint32_t>& extra);
  void markDirty(std::int32_t node);
  void refit(std::int32_t node, BvhUpdateStats& stats);
  void recomputeLeafBox(std::int32_t leaf);
  void fitLeafSlab(std::int32_t leaf);
  void fitInternalSlab(std::int32_t node);
  void maintainQuality(std::size_t editSize, BvhUpdateStats& stats);
  static std::uint64_t nextRevision();

  // The arrays that grow with the bone are on huge pages (HugePageAllocator): queries read them scattered.
  HugePageVector<BvhNode> nodes_;
  HugePageVector<BvhSlab> slabs_;  // by node, see BvhSlab
  // Per-node bookkeeping of the local update, in one record so that an update touches one cache line per
  // node for it (four parallel arrays cost four misses per node on a large tree).
  struct NodeBook {
    std::int32_t size = 0;            // triangles in the node's subtree
    std::int32_t edits = 0;           // inserts + removals below the node since its subtree was built
    std::uint32_t touchedStamp = 0;   // == epoch_: on a path edited by the current update
    std::uint8_t dirty = 0;           // box must be refitted
  };
  HugePageVector<NodeBook> book_;
  std::vector<std::int32_t> touched_;
  std::uint32_t epoch_ = 0;
  // Leaf blocks in two sizes: kBuildLeafSize entries for a leaf built with at most that many (nearly all),
  // kLeafCapacity for the rest; a leaf never grows (updates graft new subtrees), so it keeps its block.
  HugePageVector<std::uint32_t> blocks_;  // leaf slot blocks
  HugePageVector<BvhTriangle> leafTris_;  // parallel to blocks_: the slots' triangles (leafTriangles)
  std::vector<std::uint8_t> largeBlock_;  // by block start / kBuildLeafSize: a kLeafCapacity block
  std::vector<std::int32_t> freeNodes_, freeSmallBlocks_, freeLargeBlocks_;
  HugePageVector<BvhTriangle> tris_;     // by slot
  HugePageVector<std::int32_t> leafOf_;  // by slot; -1 when the slot is not in the tree
  HugePageVector<std::uint32_t> slotMark_;  // by slot: update()'s duplicate checks (stamped, never cleared)
  std::uint32_t markStamp_ = 0;
  std::int32_t root_ = -1;
  std::uint64_t revision_ = 0;  // see revision(); from one process-wide counter
  std::size_t triangleCount_ = 0;
  double rebuildCredit_ = 0;  // triangles the quality maintenance may still re-sort (see update())
  double rebuildCreditPerEdit_ = 0.25;
};

template <class F>
void TriangleBvh::forEachSlot(std::int32_t node, F&& f) const {
  std::vector<std::int32_t> stack{node};
  while (!stack.empty()) {
    const BvhNode& n = nodes_[stack.back()];
    stack.pop_back();
    if (n.isLeaf()) {
      const std::uint32_t* s = leafSlots(n);
      for (int i = 0; i < n.count; ++i) f(s[i]);
    } else {
      stack.push_back(n.left);
      stack.push_back(n.right);
    }
  }
}

}  // namespace reamsim
