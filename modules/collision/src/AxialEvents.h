#pragma once
// Internal: the interval of back-out distances d over which a reamer triangle (bone coordinates at the
// pose, translated by -d u) touches a bone triangle; and the run-chaining shared by the BVH query and its
// brute-force reference.
#include <algorithm>
#include <limits>
#include <vector>

#include "reamsim/collision/TriangleBvh.h"

namespace reamsim::detail {

struct AxialInterval {
  bool valid = false;
  double lo = 0, hi = 0;
  Vec3 hiPoint;  // contact point of the event at hi (pose coordinates of the bone)
};

AxialInterval axialInterval(const Vec3 (&x)[3], const BvhTriangle& bone, const Vec3& u);

// Do the two triangles' shadows along u overlap (closed, with a tiny tolerance)? Exactly when the interval
// above is non-empty, at a fraction of its cost.
bool shadowsOverlap(const Vec3 (&x)[3], const BvhTriangle& bone, const Vec3& u);

// Box interval: d such that [lo, hi] - d u overlaps [blo, bhi]; false when empty.
bool axialBoxInterval(const Vec3& lo, const Vec3& hi, const Vec3& blo, const Vec3& bhi, const Vec3& u, double& dlo,
                      double& dhi);

// End of the run of intervals connected to `start` (intervals must cover `start` or chain from it).
// `reachedPoint` gets the hiPoint of the interval that ends the run.
double chainFrom(double start, std::vector<AxialInterval>& intervals, double tol, Vec3& reachedPoint);

struct AxialRun {
  bool enclosed = false;  // no surface contact at d = 0: the run starts at the first contact backing out
  bool found = true;      // false only if an enclosed configuration never meets the bone within `reach`
  double depth = 0;
  Vec3 point;
};

// The depth search of the brute-force reference, by windows (the BVH query sweeps instead, so the two
// share only the interval computation): collect(wlo, whi, out) finds the intervals of the pairs that meet
// [wlo, whi]. Windows grow geometrically from `window`; intervals are complete, only their selection is
// windowed. `touching`: the surfaces touch at d = 0.
template <class Collect>
AxialRun axialRun(Collect&& collect, double tol, double reach, double window, bool touching) {
  AxialRun run;
  std::vector<AxialInterval> intervals;
  double start = 0;
  if (!touching) {
    run.enclosed = true;
    start = std::numeric_limits<double>::infinity();
    for (double lo = 0; start == std::numeric_limits<double>::infinity() && lo < reach; window *= 2) {
      intervals.clear();
      collect(lo, lo + window, intervals);
      for (const AxialInterval& iv : intervals)
        if (iv.hi >= 0) start = std::min(start, std::max(iv.lo, 0.0));
      lo += window;
    }
    if (start == std::numeric_limits<double>::infinity()) {
      run.found = false;
      return run;
    }
  }
  double end = start;
  for (;;) {
    intervals.clear();
    collect(end - tol, end + window, intervals);
    const double next = chainFrom(end, intervals, tol, run.point);
    const bool closedRun = next < end + window || next > reach;
    end = next;
    if (closedRun) break;
    window *= 2;
  }
  run.depth = end > 0 ? end : 0;
  return run;
}

}  // namespace reamsim::detail
