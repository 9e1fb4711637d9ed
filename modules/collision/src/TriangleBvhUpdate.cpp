// The local update: removals settled along the dirty paths, additions grafted, refit, and the quality
// maintenance that rebuilds heavily edited subtrees (see the header and docs/COLLISION.md).
#include "reamsim/collision/TriangleBvh.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <string>

#include "TriangleBvhInternal.h"

namespace reamsim {

using namespace bvh_detail;

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
      freeBlock(n.left);
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
// one pass over the dirty paths (settle), so a cut that empties whole subtrees costs O(nodes touched). The
// slot leaves a hole (kRemovedEntry) that settle closes: most leaves a cut touches lose all their slots and
// are freed whole, and their triangle copies are then never written.
void TriangleBvh::removeSlot(std::uint32_t slot) {
  const std::int32_t leaf = leafOf_[slot];
  BvhNode& l = nodes_[leaf];
  std::uint32_t* s = &blocks_[std::size_t(l.left)];
  const int entries = book_[leaf].size;  // the leaf's entries when this update began, holes included
  for (int i = 0; i < entries; ++i)
    if (s[i] == slot) {
      s[i] = kRemovedEntry;
      --l.count;
      break;
    }
  leafOf_[slot] = -1;
  markDirty(leaf);
}

// Closes the holes removeSlot left in a leaf's block (`entries` of them were used), keeping the order.
void TriangleBvh::closeLeafHoles(const BvhNode& leaf, int entries) {
  std::uint32_t* s = &blocks_[std::size_t(leaf.left)];
  BvhTriangle* t = &leafTris_[std::size_t(leaf.left)];
  int kept = 0;
  for (int i = 0; i < entries; ++i) {
    if (s[i] == kRemovedEntry) continue;
    if (kept != i) {
      s[kept] = s[i];
      t[kept] = t[i];
    }
    ++kept;
  }
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
    if (removedBelow > 0 && N.count > 0) closeLeafHoles(N, book_[n].size);
    book_[n].edits += removedBelow;
    book_[n].size = N.count;
    if (N.count == 0) {
      freeBlock(N.left);
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
  std::vector<BuildRef> refs = refsOf(slots);
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
  if (largest == kRemovedEntry) throw std::invalid_argument("TriangleBvh::update: slot 4294967295 is reserved");
  if (slotMark_.size() <= largest) {
    const std::size_t need = std::size_t(largest) + 1;
    if (need > slotMark_.capacity()) slotMark_.reserve(need + need / 4);  // as tris_ grows below
    slotMark_.resize(need, 0);
  }
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

  revision_ = nextRevision();
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
      // One Morton build over the new triangles (they come from one place), then grafted into the tree.
      std::vector<BuildRef> refs = refsOf(addedSlots);
      graft(buildMorton(refs, -1), stats);
    }
  }
  refit(root_, stats);
  maintainQuality(removedSlots.size() + addedSlots.size(), stats);
  stats.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

}  // namespace reamsim
