// Building the hierarchy: from a mesh or triangles, the binned SAH build (whole tree, maintenance
// rebuilds), the Morton build (the update's grafts), leaves, and the slabs beside the boxes.
#include "reamsim/collision/TriangleBvh.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>
#include <string>

#include "TriangleBvhInternal.h"

namespace reamsim {

using namespace bvh_detail;

namespace {
constexpr int kBins = 12;
}  // namespace

TriangleBvh::BuildRef TriangleBvh::refOf(std::uint32_t slot) const {
  BuildRef r;
  paddedBox(tris_[slot], r.lo, r.hi);
  r.centroid = (r.lo + r.hi) * 0.5;
  r.slot = slot;
  return r;
}

std::vector<TriangleBvh::BuildRef> TriangleBvh::refsOf(const std::vector<std::uint32_t>& slots) const {
  std::vector<BuildRef> refs;
  refs.reserve(slots.size());
  for (std::uint32_t s : slots) refs.push_back(refOf(s));
  return refs;
}

TriangleBvh TriangleBvh::fromMesh(const TriangleMesh& mesh) {
  std::vector<std::uint32_t> slots(mesh.triangles.size());
  std::vector<BvhTriangle> tris(mesh.triangles.size());
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    const Triangle& t = mesh.triangles[i];
    for (std::uint32_t v : t)
      if (v >= mesh.vertices.size())
        throw std::invalid_argument("TriangleBvh: triangle " + std::to_string(i) + " uses vertex " + std::to_string(v) +
                                    " of " + std::to_string(mesh.vertices.size()));
    slots[i] = static_cast<std::uint32_t>(i);
    tris[i] = {mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]};
  }
  return fromTriangles(slots, tris);
}

TriangleBvh TriangleBvh::fromTriangles(const std::vector<std::uint32_t>& slots,
                                       const std::vector<BvhTriangle>& triangles) {
  if (slots.size() != triangles.size())
    throw std::invalid_argument("TriangleBvh: slots and triangles differ in number");
  TriangleBvh bvh;
  std::uint32_t maxSlot = 0;
  for (std::uint32_t s : slots) maxSlot = std::max(maxSlot, s);
  const std::size_t count = slots.empty() ? 0 : std::size_t(maxSlot) + 1;
  // Cuts add slots past the end: room for a quarter more, so the first cuts do not copy the whole array
  // (reserved before the first write: the arrays are mapped and faulted once).
  bvh.tris_.reserve(count + count / 4 + 64);
  bvh.leafOf_.reserve(bvh.tris_.capacity());
  bvh.slotMark_.reserve(bvh.tris_.capacity());  // update()'s duplicate checks: sized here, not by the first cuts
  bvh.tris_.resize(count);
  bvh.leafOf_.assign(count, -1);
  bvh.slotMark_.assign(count, 0);
  for (std::size_t i = 0; i < slots.size(); ++i) {
    const BvhTriangle& t = triangles[i];
    if (!isFinite(t.a) || !isFinite(t.b) || !isFinite(t.c))
      throw std::invalid_argument("TriangleBvh: triangle " + std::to_string(i) + " has a non-finite coordinate");
    if (bvh.leafOf_[slots[i]] != -1) throw std::invalid_argument("TriangleBvh: slot " + std::to_string(slots[i]) + " given twice");
    bvh.leafOf_[slots[i]] = -2;  // marks "present" until the build assigns leaves
    bvh.tris_[slots[i]] = t;
  }
  bvh.rebuild();
  return bvh;
}

std::uint64_t TriangleBvh::nextRevision() {
  static std::atomic<std::uint64_t> counter{0};
  return ++counter;
}

void TriangleBvh::rebuild() {
  revision_ = nextRevision();
  std::vector<BuildRef> refs;
  refs.reserve(tris_.size());
  for (std::uint32_t s = 0; s < leafOf_.size(); ++s) {
    if (leafOf_[s] == -1) continue;
    refs.push_back(refOf(s));
  }
  nodes_.clear();
  slabs_.clear();
  book_.clear();
  touched_.clear();
  blocks_.clear();
  leafTris_.clear();
  largeBlock_.clear();
  freeNodes_.clear();
  freeSmallBlocks_.clear();
  freeLargeBlocks_.clear();
  const std::size_t expectNodes = refs.size() + 16;  // ~2 n / leaf size, with room for later edits
  nodes_.reserve(expectNodes);
  slabs_.reserve(expectNodes);
  book_.reserve(expectNodes);
  // A build's leaves hold ~3 triangles in blocks of 4 (~1.3 entries a triangle), with room for the edits of
  // later cuts before the arrays (~100 MiB at 400k faces) must move.
  blocks_.reserve(2 * refs.size() + 64);
  leafTris_.reserve(blocks_.capacity());
  triangleCount_ = refs.size();
  root_ = refs.empty() ? -1 : buildSubtree(refs, 0, refs.size(), -1);
  layOutInPairBlocks();
  rebuildCredit_ = 0;
}

// Renumbers the nodes (a fresh build's, none freed) so that the two children of the root, and of every node
// two levels below one so placed, sit side by side and are followed by their own children: a block of up to
// six nodes two levels deep, the blocks of a subtree together. Random queries on a 400k tree find most
// nodes they bound cold, and bound both children of every node they open: side by side, the two share a
// pair of cache lines (min distance ~7 % faster at 405k, first contact ~4 %; docs/COLLISION.md, session 22).
void TriangleBvh::layOutInPairBlocks() {
  if (root_ < 0) return;
  const std::size_t n = nodes_.size();
  std::vector<std::int32_t> newIndex(n, -1);
  std::int32_t next = 0;
  newIndex[std::size_t(root_)] = next++;
  std::vector<std::int32_t> owners{root_};  // nodes whose children's block is still to be placed
  while (!owners.empty()) {
    const BvhNode& P = nodes_[std::size_t(owners.back())];
    owners.pop_back();
    if (P.isLeaf()) continue;
    const std::int32_t children[2] = {P.left, P.right};
    for (std::int32_t c : children) newIndex[std::size_t(c)] = next++;
    std::int32_t grandchildren[4];
    int count = 0;
    for (std::int32_t c : children) {
      const BvhNode& C = nodes_[std::size_t(c)];
      if (C.isLeaf()) continue;
      newIndex[std::size_t(C.left)] = next++;
      newIndex[std::size_t(C.right)] = next++;
      grandchildren[count++] = C.left;
      grandchildren[count++] = C.right;
    }
    for (int j = count; j-- > 0;) owners.push_back(grandchildren[j]);  // the first one's subtree next
  }
  // Moved in place, cycle by cycle (every node of a fresh build is reached, so newIndex is a permutation):
  // copies of the arrays would cost a page fault per 4 KiB on a 400k tree. Links are renumbered after.
  std::vector<bool> placed(n, false);
  for (std::size_t start = 0; start < n; ++start) {
    if (placed[start]) continue;
    BvhNode node = nodes_[start];
    BvhSlab slab = slabs_[start];
    NodeBook book = book_[start];
    std::size_t from = start;  // where the carried node was
    for (;;) {
      const std::size_t to = std::size_t(newIndex[from]);
      placed[to] = true;
      if (to == start) {
        nodes_[to] = node;
        slabs_[to] = slab;
        book_[to] = book;
        break;
      }
      std::swap(node, nodes_[to]);
      std::swap(slab, slabs_[to]);
      std::swap(book, book_[to]);
      from = to;
    }
  }
  auto renumbered = [&](std::int32_t i) { return i < 0 ? i : newIndex[std::size_t(i)]; };
  for (BvhNode& nd : nodes_) {
    nd.parent = renumbered(nd.parent);
    if (!nd.isLeaf()) {  // a leaf's `left` is its slot block
      nd.left = renumbered(nd.left);
      nd.right = renumbered(nd.right);
    }
  }
  for (std::int32_t& leaf : leafOf_)
    if (leaf >= 0) leaf = newIndex[std::size_t(leaf)];
  root_ = 0;
}

std::int32_t TriangleBvh::allocNode() {
  if (!freeNodes_.empty()) {
    const std::int32_t n = freeNodes_.back();
    freeNodes_.pop_back();
    nodes_[n] = BvhNode{};
    slabs_[n] = BvhSlab{};
    book_[n] = NodeBook{};
    return n;
  }
  nodes_.emplace_back();
  slabs_.emplace_back();
  book_.emplace_back();
  return static_cast<std::int32_t>(nodes_.size() - 1);
}

// The start of a free block of kBuildLeafSize entries (entries <= kBuildLeafSize) or kLeafCapacity.
std::int32_t TriangleBvh::allocBlock(std::size_t entries) {
  const bool large = entries > std::size_t(kBuildLeafSize);
  std::vector<std::int32_t>& freeList = large ? freeLargeBlocks_ : freeSmallBlocks_;
  if (!freeList.empty()) {
    const std::int32_t b = freeList.back();
    freeList.pop_back();
    return b;
  }
  const std::size_t start = blocks_.size();
  blocks_.resize(start + (large ? kLeafCapacity : kBuildLeafSize));
  leafTris_.resize(blocks_.size());
  largeBlock_.resize(blocks_.size() / kBuildLeafSize, 0);
  largeBlock_[start / kBuildLeafSize] = large;
  return static_cast<std::int32_t>(start);
}

void TriangleBvh::freeBlock(std::int32_t start) {
  (largeBlock_[std::size_t(start) / kBuildLeafSize] ? freeLargeBlocks_ : freeSmallBlocks_).push_back(start);
}

std::int32_t TriangleBvh::makeLeaf(const BuildRef* refs, std::size_t n, std::int32_t parent) {
  const std::int32_t node = allocNode();
  const std::int32_t block = allocBlock(n);
  Vec3 lo = kEmptyLo, hi = kEmptyHi;
  std::uint32_t* out = &blocks_[std::size_t(block)];
  BvhTriangle* outTris = &leafTris_[std::size_t(block)];
  for (std::size_t i = 0; i < n; ++i) {
    out[i] = refs[i].slot;
    outTris[i] = tris_[refs[i].slot];
    leafOf_[refs[i].slot] = node;
    grow(lo, hi, refs[i].lo, refs[i].hi);
  }
  BvhNode& nd = nodes_[node];
  nd.lo = lo;
  nd.hi = hi;
  nd.parent = parent;
  nd.left = block;
  nd.right = -1;
  nd.count = static_cast<std::int32_t>(n);
  book_[node].size = static_cast<std::int32_t>(n);
  fitLeafSlab(node);
  return node;
}

std::int32_t TriangleBvh::buildSubtree(std::vector<BuildRef>& refs, std::size_t begin, std::size_t end,
                                       std::int32_t parent) {
  Vec3 lo = kEmptyLo, hi = kEmptyHi, clo = kEmptyLo, chi = kEmptyHi;
  for (std::size_t i = begin; i < end; ++i) {
    grow(lo, hi, refs[i].lo, refs[i].hi);
    grow(clo, chi, refs[i].centroid, refs[i].centroid);
  }
  return buildRange(refs, begin, end, parent, lo, hi, clo, chi);
}

// Binned SAH along the longest centroid axis (a third of the work of trying all three, for an SAH cost within
// a few percent on the bundled scapula); the bins also give both children's bounds, so each level makes two
// passes over its triangles (binning, partition). Small ranges split at the median.
std::int32_t TriangleBvh::buildRange(std::vector<BuildRef>& refs, std::size_t begin, std::size_t end,
                                     std::int32_t parent, const Vec3& lo, const Vec3& hi, const Vec3& clo,
                                     const Vec3& chi) {
  const std::size_t n = end - begin;
  if (n <= std::size_t(kBuildLeafSize)) return makeLeaf(&refs[begin], n, parent);
  const Vec3 ext = chi - clo;
  const int axis = (ext.x >= ext.y && ext.x >= ext.z) ? 0 : (ext.y >= ext.z ? 1 : 2);
  const double extent = ext[axis];
  const double parentArea = area(lo, hi);

  std::size_t mid = begin;
  Vec3 llo = kEmptyLo, lhi = kEmptyHi, lclo = kEmptyLo, lchi = kEmptyHi;
  Vec3 rlo = kEmptyLo, rhi = kEmptyHi, rclo = kEmptyLo, rchi = kEmptyHi;
  bool split = false;
  if (extent > 0 && n > 12) {
    const double scale = kBins / extent, c0 = clo[axis];
    int counts[kBins] = {};
    Vec3 blo[kBins], bhi[kBins], bclo[kBins], bchi[kBins];
    for (int b = 0; b < kBins; ++b) { blo[b] = bclo[b] = kEmptyLo; bhi[b] = bchi[b] = kEmptyHi; }
    for (std::size_t i = begin; i < end; ++i) {
      const BuildRef& r = refs[i];
      const int b = std::min(kBins - 1, static_cast<int>((r.centroid[axis] - c0) * scale));
      ++counts[b];
      grow(blo[b], bhi[b], r.lo, r.hi);
      grow(bclo[b], bchi[b], r.centroid, r.centroid);
    }
    double rightArea[kBins];
    int rightCount[kBins];
    Vec3 slo = kEmptyLo, shi = kEmptyHi;
    int rc = 0;
    for (int b = kBins - 1; b > 0; --b) {
      grow(slo, shi, blo[b], bhi[b]);
      rc += counts[b];
      rightArea[b] = area(slo, shi);
      rightCount[b] = rc;
    }
    double bestCost = std::numeric_limits<double>::infinity();
    int bestSplit = -1, lc = 0;
    slo = kEmptyLo;
    shi = kEmptyHi;
    for (int b = 1; b < kBins; ++b) {
      grow(slo, shi, blo[b - 1], bhi[b - 1]);
      lc += counts[b - 1];
      if (lc == 0 || rightCount[b] == 0) continue;
      const double cost = 1.0 + (area(slo, shi) * lc + rightArea[b] * rightCount[b]) / parentArea;
      if (cost < bestCost) { bestCost = cost; bestSplit = b; }
    }
    if (bestSplit > 0) {
      if (n <= std::size_t(kLeafCapacity) && !(bestCost < double(n))) return makeLeaf(&refs[begin], n, parent);
      for (int b = 0; b < kBins; ++b) {
        if (b < bestSplit) { grow(llo, lhi, blo[b], bhi[b]); grow(lclo, lchi, bclo[b], bchi[b]); }
        else { grow(rlo, rhi, blo[b], bhi[b]); grow(rclo, rchi, bclo[b], bchi[b]); }
      }
      auto it = std::partition(refs.begin() + begin, refs.begin() + end, [&](const BuildRef& r) {
        return std::min(kBins - 1, static_cast<int>((r.centroid[axis] - c0) * scale)) < bestSplit;
      });
      mid = static_cast<std::size_t>(it - refs.begin());
      split = mid > begin && mid < end;
    }
  }
  if (!split) {
    if (n <= std::size_t(kLeafCapacity) && extent > 0 && n > 12) return makeLeaf(&refs[begin], n, parent);
    // Median on the longest centroid axis (small ranges, or centroids that bins cannot separate).
    mid = begin + n / 2;
    std::nth_element(refs.begin() + begin, refs.begin() + mid, refs.begin() + end,
                     [axis](const BuildRef& a, const BuildRef& b) { return a.centroid[axis] < b.centroid[axis]; });
    llo = lclo = rlo = rclo = kEmptyLo;
    lhi = lchi = rhi = rchi = kEmptyHi;
    for (std::size_t i = begin; i < mid; ++i) { grow(llo, lhi, refs[i].lo, refs[i].hi); grow(lclo, lchi, refs[i].centroid, refs[i].centroid); }
    for (std::size_t i = mid; i < end; ++i) { grow(rlo, rhi, refs[i].lo, refs[i].hi); grow(rclo, rchi, refs[i].centroid, refs[i].centroid); }
  }

  const std::int32_t node = allocNode();
  nodes_[node].parent = parent;
  const std::int32_t left = buildRange(refs, begin, mid, node, llo, lhi, lclo, lchi);
  const std::int32_t right = buildRange(refs, mid, end, node, rlo, rhi, rclo, rchi);
  setChildren(node, left, right, lo, hi, n);
  return node;
}

void TriangleBvh::setChildren(std::int32_t node, std::int32_t left, std::int32_t right, const Vec3& lo, const Vec3& hi,
                              std::size_t size) {
  BvhNode& nd = nodes_[node];
  nd.left = left;
  nd.right = right;
  nd.count = -1;
  nd.lo = lo;
  nd.hi = hi;
  book_[node].size = static_cast<std::int32_t>(size);
  fitInternalSlab(node);
}

namespace {
// Spreads the low 10 bits of v to every third bit (the usual Morton interleave).
std::uint32_t spreadBits(std::uint32_t v) {
  v &= 0x3FFu;
  v = (v | (v << 16)) & 0x030000FFu;
  v = (v | (v << 8)) & 0x0300F00Fu;
  v = (v | (v << 4)) & 0x030C30C3u;
  v = (v | (v << 2)) & 0x09249249u;
  return v;
}
}  // namespace

// The graft build: triangles sorted along a Morton curve of their centroids (30-bit codes over the
// centroids' cube) and split where the codes' leading bit changes (a linear BVH). A third of the binned SAH
// build's time for the few thousand triangles a cut adds (measured: the update adding 3,000 triangles to
// the 400k scapula, 0.28-0.40 against 0.97-1.09 ms); on a patch of surface the SAH cost it gives up is
// small (after 1,529 cuts 1.264x a fresh build against 1.26x), and the maintenance pass rebuilds with SAH.
std::int32_t TriangleBvh::buildMorton(std::vector<BuildRef>& refs, std::int32_t parent) {
  const std::size_t n = refs.size();
  Vec3 clo = kEmptyLo, chi = kEmptyHi;
  for (const BuildRef& r : refs) grow(clo, chi, r.centroid, r.centroid);
  const Vec3 ext = chi - clo;
  const double longest = std::max({ext.x, ext.y, ext.z});
  const double scale = longest > 0 ? 1023.0 / longest : 0.0;
  std::vector<std::uint32_t> codes(n), order(n), codesTmp(n), orderTmp(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 q = (refs[i].centroid - clo) * scale;
    codes[i] = (spreadBits(std::uint32_t(q.x)) << 2) | (spreadBits(std::uint32_t(q.y)) << 1) | spreadBits(std::uint32_t(q.z));
    order[i] = static_cast<std::uint32_t>(i);
  }
  // LSD radix sort of the 30-bit codes, 10 bits a pass (a third of std::sort's time at a few thousand).
  for (int shift = 0; shift < 30; shift += 10) {
    std::uint32_t start[1025] = {};
    for (std::size_t i = 0; i < n; ++i) ++start[((codes[i] >> shift) & 0x3FFu) + 1];
    for (int b = 0; b < 1024; ++b) start[b + 1] += start[b];
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t at = start[(codes[i] >> shift) & 0x3FFu]++;
      codesTmp[at] = codes[i];
      orderTmp[at] = order[i];
    }
    codes.swap(codesTmp);
    order.swap(orderTmp);
  }
  std::vector<BuildRef> sorted(n);
  for (std::size_t i = 0; i < n; ++i) sorted[i] = refs[order[i]];
  return mortonRange(sorted.data(), codes.data(), n, parent);
}

std::int32_t TriangleBvh::mortonRange(const BuildRef* refs, const std::uint32_t* codes, std::size_t n,
                                      std::int32_t parent) {
  if (n <= std::size_t(kBuildLeafSize)) return makeLeaf(refs, n, parent);
  std::size_t mid = n / 2;  // equal codes: split in the middle
  const std::uint32_t differ = codes[0] ^ codes[n - 1];
  if (differ != 0) {
    // First index whose code has the highest differing bit set (codes are sorted).
    const std::uint32_t bit = 1u << (31 - __builtin_clz(differ));
    const std::uint32_t prefix = codes[0] & ~(bit | (bit - 1));
    mid = std::size_t(std::lower_bound(codes, codes + n, prefix | bit) - codes);
  }
  const std::int32_t node = allocNode();
  nodes_[node].parent = parent;
  const std::int32_t left = mortonRange(refs, codes, mid, node);
  const std::int32_t right = mortonRange(refs + mid, codes + mid, n - mid, node);
  Vec3 lo = nodes_[left].lo, hi = nodes_[left].hi;
  grow(lo, hi, nodes_[right].lo, nodes_[right].hi);
  setChildren(node, left, right, lo, hi, n);
  return node;
}

void TriangleBvh::recomputeLeafBox(std::int32_t leaf) {
  BvhNode& l = nodes_[leaf];
  Vec3 lo = kEmptyLo, hi = kEmptyHi;
  const BvhTriangle* t = leafTriangles(l);
  for (int i = 0; i < l.count; ++i) {
    Vec3 tlo, thi;
    paddedBox(t[i], tlo, thi);
    grow(lo, hi, tlo, thi);
  }
  l.lo = lo;
  l.hi = hi;
  fitLeafSlab(leaf);
}

void TriangleBvh::fitLeafSlab(std::int32_t leaf) {
  const BvhNode& l = nodes_[leaf];
  BvhSlab& sl = slabs_[leaf];
  const BvhTriangle* tris = leafTriangles(l);
  Vec3 sum;
  for (int i = 0; i < l.count; ++i) {
    const BvhTriangle& t = tris[i];
    sum += cross(t.b - t.a, t.c - t.a);
  }
  const double len = norm(sum);
  sl.normalSum = sum;
  sl.axis = len > 1e-300 ? sum / len : Vec3{0, 0, 1};
  double lo = kInf, hi = -kInf;
  for (int i = 0; i < l.count; ++i) {
    const BvhTriangle& t = tris[i];
    for (const Vec3* v : {&t.a, &t.b, &t.c}) {
      const double d = dot(sl.axis, *v);
      lo = mn(lo, d);
      hi = mx(hi, d);
    }
  }
  // As wide a pad as the boxes' (paddedBox), so the slab never cuts off what a box test would keep.
  const Vec3 d = l.hi - l.lo;
  const double mag = std::max({std::abs(l.lo.x), std::abs(l.lo.y), std::abs(l.lo.z), std::abs(l.hi.x),
                               std::abs(l.hi.y), std::abs(l.hi.z)});
  const double pad = kBoxPadRelative * (d.x + d.y + d.z) + 1e-12 * (1 + mag);
  sl.lo = lo - pad;
  sl.hi = hi + pad;
}

void TriangleBvh::fitInternalSlab(std::int32_t node) {
  const BvhNode& n = nodes_[node];
  BvhSlab& sl = slabs_[node];
  const BvhSlab &a = slabs_[n.left], &b = slabs_[n.right];
  sl.normalSum = a.normalSum + b.normalSum;
  const double len = norm(sl.normalSum);
  sl.axis = len > 1e-300 ? sl.normalSum / len : Vec3{0, 0, 1};
  double alo, ahi, blo, bhi;
  regionRange(nodes_[n.left].lo, nodes_[n.left].hi, a, sl.axis, alo, ahi);
  regionRange(nodes_[n.right].lo, nodes_[n.right].hi, b, sl.axis, blo, bhi);
  sl.lo = mn(alo, blo);
  sl.hi = mx(ahi, bhi);
}

}  // namespace reamsim
