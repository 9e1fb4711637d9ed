#pragma once
// Internal to the local subtraction: which side of the other surface each face of one surface lies on,
// decided for groups of faces at once. Far faces (those that meet no face of the other surface) are
// grouped with the faces across their edges before the corefinement, on a second thread; the near faces'
// components, known only after it, are joined in afterwards.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace reamsim::csg {

enum Side : signed char { kUndecided = -1, kOutside = 0, kInside = 1 };

// Union-find over the far faces [0, farCount) and, once added, the near components after them; each group
// has one side.
class SideGroups {
 public:
  explicit SideGroups(std::size_t farCount = 0) : farCount_(farCount) { grow(farCount); }
  std::size_t far(std::size_t j) const { return j; }
  std::size_t near(std::size_t c) const { return farCount_ + c; }
  void addNearComponents(std::size_t count) { grow(count); }
  void join(std::size_t a, std::size_t b) {
    a = root(a);
    b = root(b);
    if (a != b) parent_[a] = b;
  }
  // False when the group has the other side already; kUndecided changes nothing.
  bool setSide(std::size_t e, Side s) {
    if (s == kUndecided) return true;
    Side& g = side_[root(e)];
    if (g != kUndecided && g != s) return false;
    g = s;
    return true;
  }
  Side side(std::size_t e) { return side_[root(e)]; }
  bool anyFarUndecided() {
    for (std::size_t j = 0; j < farCount_; ++j)
      if (side(j) == kUndecided) return true;
    return false;
  }

 private:
  void grow(std::size_t count) {
    const std::size_t n = parent_.size();
    parent_.resize(n + count);
    side_.resize(n + count, kUndecided);
    for (std::size_t i = n; i < parent_.size(); ++i) parent_[i] = i;
  }
  std::size_t root(std::size_t e) {
    while (parent_[e] != e) e = parent_[e] = parent_[parent_[e]];
    return e;
  }
  std::size_t farCount_ = 0;
  std::vector<std::size_t> parent_;
  std::vector<Side> side_;
};

// The far faces of one surface, grouped: far faces across an edge joined, and each edge whose neighbour is
// a near face kept (as that face's directed edge b → a, in the near mesh's vertex handles V) to be joined
// with the near face's component once the components are known.
template <class V>
struct FarFaceGroups {
  static constexpr std::uint32_t kNoFace = std::numeric_limits<std::uint32_t>::max();
  struct ToNear {
    std::uint32_t farFace;
    V b, a;
  };
  std::vector<std::uint32_t> faces;  // the far faces, in the caller's numbering
  SideGroups groups;
  std::vector<ToNear> toNear;

  // farAcross(j, i): the far index of the face across edge i of far face j, or kNoFace; nearEdge(j, i, b, a)
  // sets the near face's directed edge across it and returns false when there is none.
  template <class FarAcross, class NearEdge>
  void group(FarAcross&& farAcross, NearEdge&& nearEdge) {
    groups = SideGroups(faces.size());
    toNear.clear();
    for (std::size_t j = 0; j < faces.size(); ++j)
      for (int i = 0; i < 3; ++i) {
        V b, a;
        if (const std::uint32_t f = farAcross(j, i); f != kNoFace)
          groups.join(groups.far(j), groups.far(f));
        else if (nearEdge(j, i, b, a))
          toNear.push_back({std::uint32_t(j), b, a});
      }
  }
  // After the corefinement: the near components (count of them; component(b, a) is the component of the
  // near face with directed edge b → a, or −1).
  template <class Component>
  void joinNear(std::size_t count, Component&& component) {
    groups.addNearComponents(count);
    for (const ToNear& e : toNear)
      if (const int c = component(e.b, e.a); c >= 0) groups.join(groups.far(e.farFace), groups.near(std::size_t(c)));
  }
};

}  // namespace reamsim::csg
