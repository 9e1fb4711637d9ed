#include "ReamerMotion.h"

#include <cmath>

namespace reamsim::ui {
namespace {

// Rodrigues: v rotated by `deg` about the unit axis k.
Vec3 rotate(const Vec3& v, const Vec3& k, double deg) {
  const double a = deg * M_PI / 180.0, c = std::cos(a), s = std::sin(a);
  return v * c + cross(k, v) * s + k * (dot(k, v) * (1 - c));
}

}  // namespace

const std::vector<MoveInfo>& reamerMoves() {
  // Thesis keys: arrows move in X/Y, x/z in Z, a/s rotate about X, r/e about Y, d/f about Z.
  static const std::vector<MoveInfo> moves = {
      {ReamerMove::XPlus, "move_x_plus", "Move +X", "Right"},
      {ReamerMove::XMinus, "move_x_minus", "Move −X", "Left"},
      {ReamerMove::YPlus, "move_y_plus", "Move +Y", "Up"},
      {ReamerMove::YMinus, "move_y_minus", "Move −Y", "Down"},
      {ReamerMove::ZPlus, "move_z_plus", "Move +Z", "X"},
      {ReamerMove::ZMinus, "move_z_minus", "Move −Z", "Z"},
      {ReamerMove::RotXPlus, "rot_x_plus", "Rotate +X", "A"},
      {ReamerMove::RotXMinus, "rot_x_minus", "Rotate −X", "S"},
      {ReamerMove::RotYPlus, "rot_y_plus", "Rotate +Y", "R"},
      {ReamerMove::RotYMinus, "rot_y_minus", "Rotate −Y", "E"},
      {ReamerMove::RotZPlus, "rot_z_plus", "Rotate +Z", "D"},
      {ReamerMove::RotZMinus, "rot_z_minus", "Rotate −Z", "F"},
      {ReamerMove::FeedForward, "feed_forward", "Feed along axis", "PgDown"},
      {ReamerMove::FeedBack, "feed_back", "Retract along axis", "PgUp"},
  };
  return moves;
}

Pose applyMove(const Pose& pose, ReamerMove move, double stepMm, double stepDeg) {
  Pose p = pose;
  switch (move) {
    case ReamerMove::XPlus: p.tip.x += stepMm; break;
    case ReamerMove::XMinus: p.tip.x -= stepMm; break;
    case ReamerMove::YPlus: p.tip.y += stepMm; break;
    case ReamerMove::YMinus: p.tip.y -= stepMm; break;
    case ReamerMove::ZPlus: p.tip.z += stepMm; break;
    case ReamerMove::ZMinus: p.tip.z -= stepMm; break;
    case ReamerMove::RotXPlus: p.axis = rotate(p.axis, {1, 0, 0}, stepDeg); break;
    case ReamerMove::RotXMinus: p.axis = rotate(p.axis, {1, 0, 0}, -stepDeg); break;
    case ReamerMove::RotYPlus: p.axis = rotate(p.axis, {0, 1, 0}, stepDeg); break;
    case ReamerMove::RotYMinus: p.axis = rotate(p.axis, {0, 1, 0}, -stepDeg); break;
    case ReamerMove::RotZPlus: p.axis = rotate(p.axis, {0, 0, 1}, stepDeg); break;
    case ReamerMove::RotZMinus: p.axis = rotate(p.axis, {0, 0, 1}, -stepDeg); break;
    case ReamerMove::FeedForward: p = advancedAlongAxis(pose, stepMm); break;
    case ReamerMove::FeedBack: p = advancedAlongAxis(pose, -stepMm); break;
  }
  p.axis = normalized(p.axis);  // keeps rounding from accumulating over many key presses
  return p;
}

}  // namespace reamsim::ui
