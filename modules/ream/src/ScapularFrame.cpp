#include "reamsim/ream/ScapularFrame.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>

namespace reamsim {
namespace {

constexpr double kMinSeparationMm = 5;
constexpr double kMinTriangleAngleDeg = 5;
constexpr double kMaxAngleDeg = 89;
constexpr double kPi = 3.14159265358979323846;

double radians(double deg) { return deg * kPi / 180; }
double degrees(double rad) { return rad * 180 / kPi; }
bool finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

std::string name(ScapulaLandmark which) { return displayName(which); }

// A number for a message, with a decimal point whatever the process's locale (std::to_string follows it).
std::string number(double value) {
  char buffer[64];
  const auto r = std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::fixed, 2);
  return r.ec == std::errc() ? std::string(buffer, r.ptr) : "?";
}

// The smallest angle of the triangle (a, b, c), in degrees: near 0 when the three lie near one line.
double smallestAngleDeg(const Vec3& a, const Vec3& b, const Vec3& c) {
  auto angleAt = [](const Vec3& p, const Vec3& q, const Vec3& r) {
    const Vec3 u = normalized(q - p), v = normalized(r - p);
    return degrees(std::acos(std::clamp(dot(u, v), -1.0, 1.0)));
  };
  return std::min({angleAt(a, b, c), angleAt(b, c, a), angleAt(c, a, b)});
}

}  // namespace

ScapularFrame scapularFrame(const ScapulaLandmarks& landmarks) {
  for (ScapulaLandmark which : kScapulaLandmarks) {
    if (!landmarks[which]) throw std::invalid_argument("the " + name(which) + " is not placed");
    if (!finite(*landmarks[which])) throw std::invalid_argument("the " + name(which) + " has a non-finite coordinate");
  }
  if (landmarks.side == BodySide::Unspecified)
    throw std::invalid_argument("the side (right or left scapula) is not given");
  const Vec3 gc = *landmarks[ScapulaLandmark::GlenoidCentre], ts = *landmarks[ScapulaLandmark::TrigonumScapulae],
             ai = *landmarks[ScapulaLandmark::InferiorAngle];
  const struct {
    ScapulaLandmark a, b;
  } pairs[] = {{ScapulaLandmark::GlenoidCentre, ScapulaLandmark::TrigonumScapulae},
               {ScapulaLandmark::GlenoidCentre, ScapulaLandmark::InferiorAngle},
               {ScapulaLandmark::TrigonumScapulae, ScapulaLandmark::InferiorAngle}};
  for (const auto& p : pairs) {
    const double d = norm(*landmarks[p.a] - *landmarks[p.b]);
    if (!(d >= kMinSeparationMm))
      throw std::invalid_argument("the " + name(p.a) + " and the " + name(p.b) + " are " + number(d) +
                                  " mm apart (at least " + std::to_string(int(kMinSeparationMm)) +
                                  " mm needed): place them again");
  }
  if (!(smallestAngleDeg(gc, ts, ai) >= kMinTriangleAngleDeg))
    throw std::invalid_argument("the glenoid centre, trigonum scapulae and inferior angle lie within " +
                                std::to_string(int(kMinTriangleAngleDeg)) +
                                " degrees of one line: they do not define the scapular plane");
  ScapularFrame f;
  f.origin = gc;
  f.side = landmarks.side;
  f.lateral = normalized(gc - ts);
  const Vec3 up = ts - ai;
  f.superior = normalized(up - f.lateral * dot(up, f.lateral));
  f.anterior = f.side == BodySide::Right ? cross(f.superior, f.lateral) : cross(f.lateral, f.superior);
  return f;
}

AxisAngles axisAngles(const ScapularFrame& frame, const Vec3& outward) {
  if (!finite(outward) || !(norm(outward) > 0)) throw std::invalid_argument("the axis is zero or not finite");
  const Vec3 o = normalized(outward);
  const double l = dot(o, frame.lateral);
  if (!(l > 0))
    throw std::invalid_argument("the axis points medially (" + number(degrees(std::acos(std::clamp(l, -1.0, 1.0)))) +
                                " degrees from the scapular axis): version and inclination are defined within 90 degrees");
  return {degrees(std::atan2(dot(o, frame.anterior), l)), degrees(std::atan2(dot(o, frame.superior), l))};
}

Vec3 outwardAxisFor(const ScapularFrame& frame, const AxisAngles& angles) {
  for (const double a : {angles.versionDeg, angles.inclinationDeg})
    if (!(std::abs(a) <= kMaxAngleDeg))
      throw std::invalid_argument("version and inclination must be finite and within ±" +
                                  std::to_string(int(kMaxAngleDeg)) + " degrees");
  return normalized(frame.lateral + frame.anterior * std::tan(radians(angles.versionDeg)) +
                    frame.superior * std::tan(radians(angles.inclinationDeg)));
}

double axisDeviationDeg(const Vec3& a, const Vec3& b) {
  if (!(norm(a) > 0) || !(norm(b) > 0)) return 0;
  return degrees(std::atan2(norm(cross(a, b)), dot(a, b)));  // accurate near 0 and 180, where acos is not
}

std::optional<BodySide> sideFromPatientFrame(PatientFrame frame, const ScapulaLandmarks& landmarks) {
  const std::optional<Vec3>& gc = landmarks[ScapulaLandmark::GlenoidCentre];
  const std::optional<Vec3>& ts = landmarks[ScapulaLandmark::TrigonumScapulae];
  if (frame == PatientFrame::Unspecified || !gc || !ts) return std::nullopt;
  const Vec3 lateral = *gc - *ts;
  const double length = norm(lateral);
  if (!(std::abs(lateral.x) >= 0.3 * length) || !(length > 0)) return std::nullopt;
  const bool towardPatientsLeft = (frame == PatientFrame::LPS) == (lateral.x > 0);
  return towardPatientsLeft ? BodySide::Left : BodySide::Right;
}

Pose aimedReamerPose(const ScapularFrame& frame, const AxisAngles& angles, double clearanceMm) {
  if (!std::isfinite(clearanceMm)) throw std::invalid_argument("the clearance must be finite");
  const Vec3 o = outwardAxisFor(frame, angles);
  Pose pose;
  pose.tip = frame.origin + o * clearanceMm;
  pose.axis = o * -1.0;
  return pose;
}

}  // namespace reamsim
