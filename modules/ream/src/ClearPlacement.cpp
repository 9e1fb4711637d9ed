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
  for (double d = stepMm; d <= maxRetreatMm + 1e-9; d += stepMm) {
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
  // The margin, where it is clear too (a thin ridge may come back beyond the boundary: then the step's end).
  double placed = clear + marginMm;
  if (marginMm > 0 && *touches(placed)) placed = clear;
  out.outcome = ClearPlacement::Outcome::Retreated;
  out.retreatMm = placed;
  out.pose = at(placed);
  return out;
}

}  // namespace reamsim
