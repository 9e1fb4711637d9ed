#include "reamsim/ream/ClearPlacement.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "reamsim/ream/Approach.h"

namespace reamsim {

namespace {

// The search itself, on one predicate: nullopt when it cannot tell, true when the solid is not clear there.
// `knownBlockedSteps` > 0: the poses out to step knownBlockedSteps - 1 are known not clear (from a search on a
// predicate this one implies), so the steps start at that one. `firstClearStep` (may be null) takes the step
// whose pose was the first found clear (0: the asked pose).
template <class NotClear>
ClearPlacement searchOut(const Pose& asked, double maxRetreatMm, double stepMm, double marginMm, NotClear&& notClear,
                         int knownBlockedSteps = 0, int* firstClearStep = nullptr) {
  const double steps = std::ceil(maxRetreatMm / stepMm);
  ClearPlacement out;
  out.pose = asked;
  const auto at = [&asked](double d) { return advancedAlongAxis(asked, -d); };
  const auto blocked = [&](double d) {
    ++out.queries;
    return notClear(at(d));
  };
  if (firstClearStep) *firstClearStep = 0;
  if (knownBlockedSteps == 0) {
    const std::optional<bool> atAsked = blocked(0);
    if (!atAsked) {
      out.outcome = ClearPlacement::Outcome::Unsupported;
      return out;
    }
    if (!*atAsked) return out;  // AsAsked
  }
  const int from = std::max(1, knownBlockedSteps);
  double inside = std::min((from - 1) * stepMm, maxRetreatMm);  // not clear here...
  double clear = -1;                                             // ...and clear here
  for (int k = from; k <= int(steps); ++k) {
    const double d = std::min(k * stepMm, maxRetreatMm);  // the last step ends at the reach
    const std::optional<bool> there = blocked(d);
    if (!there) {
      out.outcome = ClearPlacement::Outcome::Unsupported;
      return out;
    }
    if (!*there) {
      clear = d;
      if (firstClearStep) *firstClearStep = k;
      break;
    }
    inside = d;
  }
  if (clear < 0) {
    out.outcome = ClearPlacement::Outcome::NoRoom;
    return out;
  }
  for (int i = 0; i < 8; ++i) {  // the boundary within stepMm / 256
    const double mid = 0.5 * (inside + clear);
    (blocked(mid).value_or(true) ? inside : clear) = mid;
  }
  // The margin, where it is clear too (bone may come back within it: then the boundary's clear side itself).
  double placed = clear + marginMm;
  if (marginMm > 0 && blocked(placed).value_or(true)) placed = clear;
  out.outcome = ClearPlacement::Outcome::Retreated;
  out.retreatMm = placed;
  out.pose = at(placed);
  return out;
}

}  // namespace

// Searched on the surface touch (the first contact's start test, bounded by the ideal solid: ~30 µs a query at
// 400k faces), and the answer checked for any overlap at all (~0.2 ms: every bone triangle in the solid's box),
// which the touch does not see where the solid lies wholly inside a closed bone or holds a whole fragment. Only
// when that check fails is the search run again on the overlap itself, from the first step the touch found clear
// (a touch is an overlap: the steps before it are not clear either). Where the touch finds no room, neither does
// the overlap. An engine that can tell the touch but not the overlap gets the touch's answer.
ClearPlacement findClearPlacement(ReamEngine& engine, const BoneState& bone, std::uint64_t revision, const Pose& asked,
                                  double maxRetreatMm, double stepMm, double marginMm) {
  if (!(maxRetreatMm > 0) || !std::isfinite(maxRetreatMm) || !(stepMm > 0) || !std::isfinite(stepMm) ||
      !(marginMm >= 0) || !std::isfinite(marginMm))
    throw std::invalid_argument("findClearPlacement: maxRetreatMm and stepMm must be positive, marginMm >= 0");
  if (std::ceil(maxRetreatMm / stepMm) > 100000)
    throw std::invalid_argument("findClearPlacement: more than 100000 steps to reach maxRetreatMm");
  const auto touches = [&](const Pose& p) { return engine.touchesAt(bone, revision, p); };
  const auto overlaps = [&](const Pose& p) { return engine.overlapsAt(bone, revision, p); };
  int firstClearStep = 0;
  ClearPlacement out = searchOut(asked, maxRetreatMm, stepMm, marginMm, touches, 0, &firstClearStep);
  if (out.outcome == ClearPlacement::Outcome::Unsupported || out.outcome == ClearPlacement::Outcome::NoRoom) return out;
  const std::optional<bool> enclosed = overlaps(out.pose);
  ++out.queries;
  if (!enclosed || !*enclosed) return out;  // clear (or an engine that can only tell the touch)
  const int queriesSoFar = out.queries;
  // Not clear at the asked pose either when the touch found it clear (just checked): the steps start at 1.
  out = searchOut(asked, maxRetreatMm, stepMm, marginMm, overlaps, std::max(1, firstClearStep));
  out.queries += queriesSoFar;
  out.overlapSearch = true;
  return out;
}

}  // namespace reamsim
