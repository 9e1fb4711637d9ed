#pragma once
// The thesis's reamer keys as pure pose arithmetic (no Qt): translate the tip along the bone's X/Y/Z
// axes, rotate the feed axis about the bone's X/Y/Z axes through the tip.
#include <QString>
#include <vector>

#include "reamsim/core/Pose.h"

namespace reamsim::ui {

enum class ReamerMove {
  XPlus, XMinus, YPlus, YMinus, ZPlus, ZMinus,                 // translate (step mm)
  RotXPlus, RotXMinus, RotYPlus, RotYMinus, RotZPlus, RotZMinus,  // rotate (step degrees)
  FeedForward, FeedBack,                                       // along the reamer's own axis (step mm)
};

struct MoveInfo {
  ReamerMove move;
  const char* id;           // settings key, e.g. "move_x_plus"
  const char* label;        // menu text
  const char* defaultKey;   // QKeySequence text, as in the thesis
};
const std::vector<MoveInfo>& reamerMoves();

Pose applyMove(const Pose& pose, ReamerMove move, double stepMm, double stepDeg);

}  // namespace reamsim::ui
