#include "reamsim/ream/ClearPlacement.h"

#include <cmath>
#include <stdexcept>

#include "reamsim/ream/Approach.h"

namespace reamsim {

ClearPlacement findClearPlacement(ReamEngine& engine, const BoneState& bone, std::uint64_t revision, const Pose& asked,
                                  double maxRetreatMm, double stepMm, double marginMm) {
  if (!(maxRetreatMm > 0) || !std::isfinite(maxRetreatMm) || !(stepMm > 0) || !std::isfinite(stepMm) ||
      !(marginMm >= 0) || !std::isfinite(marginMm))
    throw std::invalid_argument("findClearPlacement: maxRetreatMm and stepMm must be positive, marginMm >= 0");
  const double steps = std::ceil(maxRetreatMm / stepMm);
  if (steps > 100000) throw std::invalid_argument("findClearPlacement: more than 100000 steps to reach maxRetreatMm");
  ClearPlacement out;
  out.pose = asked;
  const auto at = [&asked](double d) { return advancedAlongAxis(asked, -d); };
  // nullopt: the engine cannot tell (no exact query); true: the cutting solid touches the bone there.
  const auto touches = [&](double d) {
    ++out.queries;
    return engine.touchesAt(bone, revision, at(d));
  };
  const std::optional<bool> atAsked = touches(0);
  if (!atAsked) {
    out.outcome = ClearPlacement::Outcome::Unsupported;
    return out;
  }
  if (!*atAsked) return out;  // AsAsked
  double inside = 0;          // touching here...
  double clear = -1;          // ...and clear here
  for (int k = 1; k <= int(steps); ++k) {
    const double d = std::min(k * stepMm, maxRetreatMm);  // the last step ends at the reach
    if (!*touches(d)) {
      clear = d;
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
    (*touches(mid) ? inside : clear) = mid;
  }
  // The margin, where it is clear too (bone may come back within it: then the boundary's clear side itself).
  double placed = clear + marginMm;
  if (marginMm > 0 && *touches(placed)) placed = clear;
  out.outcome = ClearPlacement::Outcome::Retreated;
  out.retreatMm = placed;
  out.pose = at(placed);
  return out;
}

}  // namespace reamsim
