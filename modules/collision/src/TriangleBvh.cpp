#include "reamsim/collision/TriangleBvh.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

namespace reamsim {

namespace {

constexpr int kBins = 12;

double area(const Vec3& lo, const Vec3& hi) {
  const Vec3 d = hi - lo;
  if (d.x < 0 || d.y < 0 || d.z < 0) return 0;
  return 2 * (d.x * d.y + d.y * d.z + d.z * d.x);
}
// Written as plain selects so the compiler emits branch-free min/max (the binning loop mispredicted).
inline double mn(double a, double b) { return b < a ? b : a; }
inline double mx(double a, double b) { return a < b ? b : a; }
inline void grow(Vec3& lo, Vec3& hi, const Vec3& plo, const Vec3& phi) {
  lo.x = mn(lo.x, plo.x);
  lo.y = mn(lo.y, plo.y);
  lo.z = mn(lo.z, plo.z);
  hi.x = mx(hi.x, phi.x);
  hi.y = mx(hi.y, phi.y);
  hi.z = mx(hi.z, phi.z);
}
constexpr double kInf = std::numeric_limits<double>::infinity();
const Vec3 kEmptyLo{kInf, kInf, kInf};
const Vec3 kEmptyHi{-kInf, -kInf, -kInf};

}  // namespace

void regionRange(const Vec3& lo, const Vec3& hi, const BvhSlab& slab, const Vec3& u, double& outLo, double& outHi) {
  const Vec3 c = (lo + hi) * 0.5, h = (hi - lo) * 0.5;
  auto boxRange = [&](const Vec3& v, double& rlo, double& rhi) {
    const double vc = dot(v, c), vh = std::abs(v.x) * h.x + std::abs(v.y) * h.y + std::abs(v.z) * h.z;
    rlo = vc - vh;
    rhi = vc + vh;
  };
  double blo, bhi;
  boxRange(u, blo, bhi);
  const double a = dot(u, slab.axis);
  const Vec3 w = u - slab.axis * a;
  double wlo, whi;
  boxRange(w, wlo, whi);
  const double slo = a >= 0 ? a * slab.lo : a * slab.hi, shi = a >= 0 ? a * slab.hi : a * slab.lo;
  // Rounding of the products and sums above: relative to the magnitudes involved.
  const double pad = 1e-12 * (std::abs(dot(u, c)) + std::abs(slab.lo) + std::abs(slab.hi) + h.x + h.y + h.z) + 1e-300;
  outLo = std::max(blo, slo + wlo) - pad;
  outHi = std::min(bhi, shi + whi) + pad;
}

struct TriangleBvh::BuildRef {
  Vec3 lo, hi, centroid;
  std::uint32_t slot;
};

void TriangleBvh::paddedBox(const BvhTriangle& t, Vec3& lo, Vec3& hi) {
  lo = {std::min({t.a.x, t.b.x, t.c.x}), std::min({t.a.y, t.b.y, t.c.y}), std::min({t.a.z, t.b.z, t.c.z})};
  hi = {std::max({t.a.x, t.b.x, t.c.x}), std::max({t.a.y, t.b.y, t.c.y}), std::max({t.a.z, t.b.z, t.c.z})};
  const Vec3 d = hi - lo;
  const double mag = std::max({std::abs(lo.x), std::abs(lo.y), std::abs(lo.z), std::abs(hi.x), std::abs(hi.y),
                               std::abs(hi.z)});
  const double pad = kBoxPadRelative * (d.x + d.y + d.z) + 1e-12 * (1 + mag);
  lo -= Vec3{pad, pad, pad};
  hi += Vec3{pad, pad, pad};
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
  bvh.tris_.resize(slots.empty() ? 0 : std::size_t(maxSlot) + 1);
  bvh.leafOf_.assign(bvh.tris_.size(), -1);
  // Cuts add slots past the end: room for a quarter more, so the first cuts do not copy the whole array.
  bvh.tris_.reserve(bvh.tris_.size() + bvh.tris_.size() / 4 + 64);
  bvh.leafOf_.reserve(bvh.tris_.capacity());
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

void TriangleBvh::rebuild() {
  std::vector<BuildRef> refs;
  refs.reserve(tris_.size());
  for (std::uint32_t s = 0; s < leafOf_.size(); ++s) {
    if (leafOf_[s] == -1) continue;
    BuildRef r;
    paddedBox(tris_[s], r.lo, r.hi);
    r.centroid = (r.lo + r.hi) * 0.5;
    r.slot = s;
    refs.push_back(r);
  }
  nodes_.clear();
  slabs_.clear();
  book_.clear();
  touched_.clear();
  blocks_.clear();
  freeNodes_.clear();
  freeBlocks_.clear();
  const std::size_t expectNodes = refs.size() + 16;  // ~2 n / leaf size, with room for later edits
  nodes_.reserve(expectNodes);
  slabs_.reserve(expectNodes);
  book_.reserve(expectNodes);
  blocks_.reserve(std::size_t(kLeafCapacity) * (refs.size() / 2 + 16));
  triangleCount_ = refs.size();
  root_ = refs.empty() ? -1 : buildSubtree(refs, 0, refs.size(), -1);
  rebuildCredit_ = 0;
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

std::int32_t TriangleBvh::allocBlock() {
  if (!freeBlocks_.empty()) {
    const std::int32_t b = freeBlocks_.back();
    freeBlocks_.pop_back();
    return b;
  }
  blocks_.resize(blocks_.size() + kLeafCapacity);
  return static_cast<std::int32_t>(blocks_.size() / kLeafCapacity - 1);
}

std::int32_t TriangleBvh::makeLeaf(const BuildRef* refs, std::size_t n, std::int32_t parent) {
  const std::int32_t node = allocNode();
  const std::int32_t block = allocBlock();
  Vec3 lo = kEmptyLo, hi = kEmptyHi;
  std::uint32_t* out = &blocks_[std::size_t(block) * kLeafCapacity];
  for (std::size_t i = 0; i < n; ++i) {
    out[i] = refs[i].slot;
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
  BvhNode& nd = nodes_[node];
  nd.left = left;
  nd.right = right;
  nd.count = -1;
  nd.lo = lo;
  nd.hi = hi;
  book_[node].size = static_cast<std::int32_t>(n);
  fitInternalSlab(node);
  return node;
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
  BvhNode& nd = nodes_[node];
  nd.left = left;
  nd.right = right;
  nd.count = -1;
  nd.lo = nodes_[left].lo;
  nd.hi = nodes_[left].hi;
  grow(nd.lo, nd.hi, nodes_[right].lo, nodes_[right].hi);
  book_[node].size = static_cast<std::int32_t>(n);
  fitInternalSlab(node);
  return node;
}

void TriangleBvh::replaceChild(std::int32_t parent, std::int32_t oldChild, std::int32_t newChild) {
  if (parent < 0) {
    root_ = newChild;
  } else if (nodes_[parent].left == oldChild) {
    nodes_[parent].left = newChild;
  } else {
    nodes_[parent].right = newChild;
  }
  if (newChild >= 0) nodes_[newChild].parent = parent;
}

void TriangleBvh::freeSubtree(std::int32_t node, std::vector<std::uint32_t>* slotsOut) {
  std::vector<std::int32_t> stack{node};
  while (!stack.empty()) {
    const std::int32_t i = stack.back();
    stack.pop_back();
    const BvhNode n = nodes_[i];
    if (n.isLeaf()) {
      if (slotsOut) {
        const std::uint32_t* s = leafSlots(n);
        slotsOut->insert(slotsOut->end(), s, s + n.count);
      }
      freeBlocks_.push_back(n.left);
    } else {
      stack.push_back(n.left);
      stack.push_back(n.right);
    }
    nodes_[i].right = -2;  // freed marker (never a valid child index)
    freeNodes_.push_back(i);
  }
}

void TriangleBvh::markDirty(std::int32_t node) {
  while (node >= 0 && !book_[node].dirty) {
    book_[node].dirty = 1;
    node = nodes_[node].parent;
  }
}

// Takes the slot out of its leaf; sizes, edit counts, emptied subtrees and boxes are settled afterwards by
// one pass over the dirty paths (settle), so a cut that empties whole subtrees costs O(nodes touched).
void TriangleBvh::removeSlot(std::uint32_t slot) {
  const std::int32_t leaf = leafOf_[slot];
  BvhNode& l = nodes_[leaf];
  std::uint32_t* s = &blocks_[std::size_t(l.left) * kLeafCapacity];
  for (int i = 0; i < l.count; ++i)
    if (s[i] == slot) {
      s[i] = s[l.count - 1];
      --l.count;
      break;
    }
  leafOf_[slot] = -1;
  markDirty(leaf);
}

// Post-order over dirty nodes: leaf sizes from their counts, internal sizes from their children, edit counts
// grow by the triangles removed below, empty leaves and nodes are freed (a node left with one child is
// replaced by it), boxes are refitted. Returns the node now standing in n's place (-1: nothing left).
std::int32_t TriangleBvh::settle(std::int32_t n, std::int32_t& removedBelow, BvhUpdateStats& stats) {
  book_[n].dirty = 0;
  touch(n);
  ++stats.refitNodes;
  BvhNode& N = nodes_[n];
  if (N.isLeaf()) {
    removedBelow = book_[n].size - N.count;
    book_[n].edits += removedBelow;
    book_[n].size = N.count;
    if (N.count == 0) {
      freeBlocks_.push_back(N.left);
      N.right = -2;
      freeNodes_.push_back(n);
      return -1;
    }
    recomputeLeafBox(n);
    return n;
  }
  std::int32_t rl = 0, rr = 0;
  const std::int32_t l = book_[N.left].dirty ? settle(N.left, rl, stats) : N.left;
  const std::int32_t r = book_[nodes_[n].right].dirty ? settle(nodes_[n].right, rr, stats) : nodes_[n].right;
  removedBelow = rl + rr;
  if (l < 0 || r < 0) {
    nodes_[n].right = -2;
    freeNodes_.push_back(n);
    return l < 0 ? r : l;  // the survivor (or -1) takes n's place; its parent is set by the caller
  }
  BvhNode& M = nodes_[n];
  M.left = l;
  M.right = r;
  nodes_[l].parent = n;
  nodes_[r].parent = n;
  book_[n].edits += removedBelow;
  book_[n].size = book_[l].size + book_[r].size;
  M.lo = nodes_[l].lo;
  M.hi = nodes_[l].hi;
  grow(M.lo, M.hi, nodes_[r].lo, nodes_[r].hi);
  fitInternalSlab(n);
  return n;
}

std::int32_t TriangleBvh::rebuildSubtree(std::int32_t node, const std::vector<std::uint32_t>& extra) {
  const std::int32_t parent = nodes_[node].parent;
  const bool wasLeft = parent >= 0 && nodes_[parent].left == node;
  std::vector<std::uint32_t> slots;
  slots.reserve(std::size_t(book_[node].size) + extra.size());
  freeSubtree(node, &slots);
  slots.insert(slots.end(), extra.begin(), extra.end());
  std::vector<BuildRef> refs(slots.size());
  for (std::size_t i = 0; i < slots.size(); ++i) {
    paddedBox(tris_[slots[i]], refs[i].lo, refs[i].hi);
    refs[i].centroid = (refs[i].lo + refs[i].hi) * 0.5;
    refs[i].slot = slots[i];
  }
  const std::int32_t fresh = buildSubtree(refs, 0, refs.size(), parent);
  if (parent < 0) {
    root_ = fresh;
  } else if (wasLeft) {
    nodes_[parent].left = fresh;
  } else {
    nodes_[parent].right = fresh;
  }
  return fresh;
}

void TriangleBvh::touch(std::int32_t node) {
  if (book_[node].touchedStamp == epoch_) return;
  book_[node].touchedStamp = epoch_;
  touched_.push_back(node);
}

// Box2D-style sibling choice: descend while moving the new box deeper lowers the surface-area cost.
std::int32_t TriangleBvh::bestSibling(const Vec3& lo, const Vec3& hi) const {
  std::int32_t n = root_;
  while (!nodes_[n].isLeaf()) {
    const BvhNode& N = nodes_[n];
    Vec3 ulo = N.lo, uhi = N.hi;
    grow(ulo, uhi, lo, hi);
    const double combined = area(ulo, uhi);
    const double here = combined;                  // new parent of n and the graft
    const double inherited = combined - area(N.lo, N.hi);
    double childCost[2];
    const std::int32_t kids[2] = {N.left, N.right};
    for (int k = 0; k < 2; ++k) {
      const BvhNode& C = nodes_[kids[k]];
      Vec3 clo = C.lo, chi = C.hi;
      grow(clo, chi, lo, hi);
      childCost[k] = area(clo, chi) - (C.isLeaf() ? 0.0 : area(C.lo, C.hi)) + inherited;
    }
    if (here <= std::min(childCost[0], childCost[1])) break;
    n = childCost[0] <= childCost[1] ? kids[0] : kids[1];
  }
  return n;
}

// Inserts a freshly built, detached subtree. A subtree spanning separate clusters (its box much larger than
// its children's together) is split and each part placed on its own.
void TriangleBvh::graft(std::int32_t sub, BvhUpdateStats& stats) {
  const BvhNode S = nodes_[sub];
  if (!S.isLeaf()) {
    const double parts = area(nodes_[S.left].lo, nodes_[S.left].hi) + area(nodes_[S.right].lo, nodes_[S.right].hi);
    if (area(S.lo, S.hi) > 2.0 * parts) {
      nodes_[sub].right = -2;
      freeNodes_.push_back(sub);
      nodes_[S.left].parent = -1;
      nodes_[S.right].parent = -1;
      graft(S.left, stats);
      graft(S.right, stats);
      return;
    }
  }
  const std::int32_t k = book_[sub].size;
  const std::int32_t sibling = bestSibling(S.lo, S.hi);
  const std::int32_t grand = nodes_[sibling].parent;
  const std::int32_t p = allocNode();
  BvhNode& P = nodes_[p];
  P.parent = grand;
  P.left = sibling;
  P.right = sub;
  P.count = -1;
  P.lo = nodes_[sibling].lo;
  P.hi = nodes_[sibling].hi;
  grow(P.lo, P.hi, S.lo, S.hi);
  book_[p].size = book_[sibling].size + k;
  fitInternalSlab(p);
  book_[p].edits = std::min(book_[sibling].size, k);  // the part that was not built together
  replaceChild(grand, sibling, p);
  nodes_[sibling].parent = p;
  nodes_[sub].parent = p;
  touch(p);
  for (std::int32_t a = grand; a >= 0; a = nodes_[a].parent) {
    book_[a].size += k;
    book_[a].edits += k;
    touch(a);
  }
  markDirty(p);
  ++stats.leafSplits;
}

void TriangleBvh::recomputeLeafBox(std::int32_t leaf) {
  BvhNode& l = nodes_[leaf];
  Vec3 lo = kEmptyLo, hi = kEmptyHi;
  const std::uint32_t* s = leafSlots(l);
  for (int i = 0; i < l.count; ++i) {
    Vec3 tlo, thi;
    paddedBox(tris_[s[i]], tlo, thi);
    grow(lo, hi, tlo, thi);
  }
  l.lo = lo;
  l.hi = hi;
  fitLeafSlab(leaf);
}

void TriangleBvh::fitLeafSlab(std::int32_t leaf) {
  const BvhNode& l = nodes_[leaf];
  BvhSlab& sl = slabs_[leaf];
  const std::uint32_t* s = leafSlots(l);
  Vec3 sum;
  for (int i = 0; i < l.count; ++i) {
    const BvhTriangle& t = tris_[s[i]];
    sum += cross(t.b - t.a, t.c - t.a);
  }
  const double len = norm(sum);
  sl.normalSum = sum;
  sl.axis = len > 1e-300 ? sum / len : Vec3{0, 0, 1};
  double lo = kInf, hi = -kInf;
  for (int i = 0; i < l.count; ++i) {
    const BvhTriangle& t = tris_[s[i]];
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

void TriangleBvh::refit(std::int32_t node, BvhUpdateStats& stats) {
  if (node < 0 || !book_[node].dirty) return;
  book_[node].dirty = 0;
  ++stats.refitNodes;
  if (nodes_[node].isLeaf()) {
    recomputeLeafBox(node);
    return;
  }
  const std::int32_t l = nodes_[node].left, r = nodes_[node].right;
  refit(l, stats);
  refit(r, stats);
  BvhNode& n = nodes_[node];
  n.lo = nodes_[l].lo;
  n.hi = nodes_[l].hi;
  grow(n.lo, n.hi, nodes_[r].lo, nodes_[r].hi);
  fitInternalSlab(node);
}

// Quality maintenance (see the header): among the nodes on the paths this update touched, rebuild those
// whose edit count exceeds kRebuildFraction of their size, smallest first, while the rebuild credit
// (rebuildCreditPerEdit_ per edited triangle, amortised) lasts. Only touched paths are scanned, so the cost
// does not grow with the tree.
void TriangleBvh::maintainQuality(std::size_t editSize, BvhUpdateStats& stats) {
  if (root_ < 0) return;
  rebuildCredit_ = std::min(rebuildCredit_ + rebuildCreditPerEdit_ * double(editSize),
                            2.0 * double(triangleCount_) + 1024.0);
  std::vector<std::int32_t> candidates;
  for (std::int32_t i : touched_)
    if (book_[i].touchedStamp == epoch_ && nodes_[i].right != -2 && !nodes_[i].isLeaf() &&
        book_[i].edits > kRebuildFraction * book_[i].size)
      candidates.push_back(i);
  std::sort(candidates.begin(), candidates.end(),
            [this](std::int32_t a, std::int32_t b) { return book_[a].size < book_[b].size; });
  for (std::int32_t node : candidates) {
    if (nodes_[node].right == -2 || nodes_[node].isLeaf() || book_[node].touchedStamp != epoch_) continue;  // freed
    if (!(book_[node].edits > kRebuildFraction * book_[node].size)) continue;  // a rebuild below already fixed it
    if (double(book_[node].size) > rebuildCredit_) continue;
    const std::int32_t e = book_[node].edits;
    const std::int32_t parent = nodes_[node].parent;
    rebuildCredit_ -= book_[node].size;
    stats.rebuiltTriangles += std::size_t(book_[node].size);
    ++stats.rebuiltSubtrees;
    if (parent < 0) stats.fullRebuild = true;
    rebuildSubtree(node, {});
    for (std::int32_t a = parent; a >= 0; a = nodes_[a].parent) book_[a].edits -= e;
  }
}

BvhUpdateStats TriangleBvh::update(const std::vector<std::uint32_t>& removedSlots,
                                   const std::vector<std::uint32_t>& addedSlots,
                                   const std::vector<BvhTriangle>& addedTriangles) {
  const auto start = std::chrono::steady_clock::now();
  if (addedSlots.size() != addedTriangles.size())
    throw std::invalid_argument("TriangleBvh::update: added slots and triangles differ in number");
  // Validate everything before touching the tree: one mark per slot (this call's stamp; +1 = removed,
  // +2 = added) instead of sorting both lists, which cost a third of a typical update.
  std::uint32_t largest = 0, largestAdded = 0;
  for (std::uint32_t s : removedSlots) largest = std::max(largest, s);
  for (std::uint32_t s : addedSlots) largestAdded = std::max(largestAdded, s);
  largest = std::max(largest, largestAdded);
  if (slotMark_.size() <= largest) slotMark_.resize(std::size_t(largest) + 1, 0);
  if (markStamp_ >= 0xFFFFFFF0u) {
    std::fill(slotMark_.begin(), slotMark_.end(), 0);
    markStamp_ = 0;
  }
  const std::uint32_t removedMark = markStamp_ + 1, addedMark = markStamp_ + 2;
  markStamp_ += 2;
  for (std::uint32_t s : removedSlots) {
    if (!contains(s)) throw std::invalid_argument("TriangleBvh::update: removed slot " + std::to_string(s) + " is not in the tree");
    if (slotMark_[s] == removedMark)
      throw std::invalid_argument("TriangleBvh::update: slot " + std::to_string(s) + " removed twice");
    slotMark_[s] = removedMark;
  }
  for (std::uint32_t s : addedSlots) {
    if (slotMark_[s] == addedMark) throw std::invalid_argument("TriangleBvh::update: slot " + std::to_string(s) + " added twice");
    if (contains(s) && slotMark_[s] != removedMark)
      throw std::invalid_argument("TriangleBvh::update: added slot " + std::to_string(s) + " is already in the tree");
    slotMark_[s] = addedMark;
  }
  // A slot both removed and added now carries the added mark; only duplicates within one list matter above.
  for (const BvhTriangle& t : addedTriangles)
    if (!isFinite(t.a) || !isFinite(t.b) || !isFinite(t.c))
      throw std::invalid_argument("TriangleBvh::update: an added triangle has a non-finite coordinate");

  BvhUpdateStats stats;
  stats.removed = removedSlots.size();
  stats.added = addedSlots.size();
  ++epoch_;
  touched_.clear();
  for (std::uint32_t s : removedSlots) removeSlot(s);
  if (root_ >= 0 && book_[root_].dirty) {
    std::int32_t removed = 0;
    root_ = settle(root_, removed, stats);
    if (root_ >= 0) nodes_[root_].parent = -1;
  }
  if (!addedSlots.empty() && largestAdded >= tris_.size()) {
    const std::size_t need = std::size_t(largestAdded) + 1;
    if (need > tris_.capacity()) {  // grow by a quarter at least, not to the exact size
      tris_.reserve(need + need / 4);
      leafOf_.reserve(need + need / 4);
    }
    tris_.resize(need);
    leafOf_.resize(need, -1);
  }
  for (std::size_t i = 0; i < addedSlots.size(); ++i) tris_[addedSlots[i]] = addedTriangles[i];
  triangleCount_ = triangleCount_ - removedSlots.size() + addedSlots.size();

  if (!addedSlots.empty()) {
    if (root_ < 0) {
      for (std::uint32_t s : addedSlots) leafOf_[s] = -2;
      rebuild();
      stats.fullRebuild = true;
    } else {
      // One SAH build over the new triangles (they come from one place), then grafted into the tree.
      std::vector<BuildRef> refs(addedSlots.size());
      for (std::size_t i = 0; i < addedSlots.size(); ++i) {
        paddedBox(tris_[addedSlots[i]], refs[i].lo, refs[i].hi);
        refs[i].centroid = (refs[i].lo + refs[i].hi) * 0.5;
        refs[i].slot = addedSlots[i];
      }
      graft(buildMorton(refs, -1), stats);
    }
  }
  refit(root_, stats);
  maintainQuality(removedSlots.size() + addedSlots.size(), stats);
  stats.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

Bounds TriangleBvh::bounds() const {
  Bounds b;
  if (root_ >= 0) {
    b.add(nodes_[root_].lo);
    b.add(nodes_[root_].hi);
  }
  return b;
}

BvhQuality TriangleBvh::quality() const {
  BvhQuality q;
  q.triangles = triangleCount_;
  if (root_ < 0) return q;
  const double rootArea = std::max(area(nodes_[root_].lo, nodes_[root_].hi), 1e-300);
  std::vector<std::pair<std::int32_t, std::size_t>> stack{{root_, 1}};
  double cost = 0;
  while (!stack.empty()) {
    const auto [i, depth] = stack.back();
    stack.pop_back();
    const BvhNode& n = nodes_[i];
    ++q.nodes;
    q.maxDepth = std::max(q.maxDepth, depth);
    const double a = area(n.lo, n.hi) / rootArea;
    if (n.isLeaf()) {
      ++q.leaves;
      cost += a * n.count;
    } else {
      cost += a;
      stack.push_back({n.left, depth + 1});
      stack.push_back({n.right, depth + 1});
    }
  }
  q.sahCost = cost;
  q.meanLeafSize = q.leaves ? double(q.triangles) / double(q.leaves) : 0;
  return q;
}

std::string TriangleBvh::validate() const {
  if (root_ < 0) return triangleCount_ == 0 ? "" : "empty tree but triangleCount != 0";
  if (nodes_[root_].parent != -1) return "root has a parent";
  std::size_t seen = 0;
  std::vector<std::int32_t> stack{root_};
  auto encloses = [](const BvhNode& outer, const Vec3& lo, const Vec3& hi) {
    return outer.lo.x <= lo.x && outer.lo.y <= lo.y && outer.lo.z <= lo.z && outer.hi.x >= hi.x &&
           outer.hi.y >= hi.y && outer.hi.z >= hi.z;
  };
  while (!stack.empty()) {
    const std::int32_t i = stack.back();
    stack.pop_back();
    const BvhNode& n = nodes_[i];
    if (n.right == -2) return "reachable node " + std::to_string(i) + " is freed";
    if (book_[i].dirty) return "node " + std::to_string(i) + " left dirty";
    if (n.isLeaf()) {
      if (n.count < 1 || n.count > kLeafCapacity) return "leaf " + std::to_string(i) + " has count " + std::to_string(n.count);
      if (book_[i].size != n.count) return "leaf " + std::to_string(i) + " size counter mismatch";
      const std::uint32_t* s = leafSlots(n);
      for (int k = 0; k < n.count; ++k) {
        if (s[k] >= leafOf_.size() || leafOf_[s[k]] != i) return "slot " + std::to_string(s[k]) + " not mapped to its leaf";
        Vec3 lo, hi;
        paddedBox(tris_[s[k]], lo, hi);
        if (!encloses(n, lo, hi)) return "leaf " + std::to_string(i) + " does not enclose slot " + std::to_string(s[k]);
        // Every slab on the path to the root holds the triangle's corners.
        for (std::int32_t a = i; a >= 0; a = nodes_[a].parent) {
          const BvhSlab& sl = slabs_[a];
          for (const Vec3* v : {&tris_[s[k]].a, &tris_[s[k]].b, &tris_[s[k]].c}) {
            const double dv = dot(sl.axis, *v);
            if (!(dv >= sl.lo && dv <= sl.hi))
              return "slab of node " + std::to_string(a) + " does not hold slot " + std::to_string(s[k]);
          }
        }
      }
      seen += std::size_t(n.count);
    } else {
      for (std::int32_t c : {n.left, n.right}) {
        if (c < 0 || std::size_t(c) >= nodes_.size()) return "bad child index";
        if (nodes_[c].parent != i) return "child " + std::to_string(c) + " has a wrong parent";
        if (!encloses(n, nodes_[c].lo, nodes_[c].hi)) return "node " + std::to_string(i) + " does not enclose its child";
      }
      if (book_[i].size != book_[n.left].size + book_[n.right].size) return "size counter mismatch at " + std::to_string(i);
      stack.push_back(n.left);
      stack.push_back(n.right);
    }
  }
  if (seen != triangleCount_) return "tree holds " + std::to_string(seen) + " triangles, expected " + std::to_string(triangleCount_);
  std::size_t mapped = 0;
  for (std::int32_t l : leafOf_) mapped += l >= 0;
  if (mapped != seen) return "slot map holds stale entries";
  return "";
}

}  // namespace reamsim
