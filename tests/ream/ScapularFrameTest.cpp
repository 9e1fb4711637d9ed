// Version and inclination of a reaming axis in the scapular frame (reamsim/ream/ScapularFrame.h), and the
// landmark files that carry the frame's points.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>

#include "reamsim/mesh/MeshError.h"
#include "reamsim/ream/DefaultCase.h"
#include "reamsim/ream/ScapularFrame.h"

namespace reamsim {
namespace {

constexpr double kPi = 3.14159265358979323846;
double rad(double deg) { return deg * kPi / 180; }

// A right scapula in RAS-like coordinates (+x the patient's right = lateral, +y anterior, +z superior).
ScapulaLandmarks rightScapula() {
  ScapulaLandmarks l;
  l.side = BodySide::Right;
  l[ScapulaLandmark::GlenoidCentre] = Vec3{60, 0, 0};
  l[ScapulaLandmark::TrigonumScapulae] = Vec3{0, 0, 0};
  l[ScapulaLandmark::InferiorAngle] = Vec3{10, 0, -100};
  return l;
}

ScapulaLandmarks mirrored(const ScapulaLandmarks& in) {
  ScapulaLandmarks out = in;
  out.side = in.side == BodySide::Right ? BodySide::Left : BodySide::Right;
  for (ScapulaLandmark which : kScapulaLandmarks) out[which]->x = -out[which]->x;
  return out;
}

TEST(ScapularFrame, AxesFollowTheLandmarksOnARightScapula) {
  const ScapularFrame f = scapularFrame(rightScapula());
  EXPECT_NEAR(norm(f.lateral - Vec3{1, 0, 0}), 0, 1e-15);
  EXPECT_NEAR(norm(f.superior - Vec3{0, 0, 1}), 0, 1e-15);
  EXPECT_NEAR(norm(f.anterior - Vec3{0, 1, 0}), 0, 1e-15);
}

TEST(ScapularFrame, AnteversionAndSuperiorTiltArePositive) {
  const ScapularFrame f = scapularFrame(rightScapula());
  const AxisAngles ante = axisAngles(f, {std::cos(rad(10)), std::sin(rad(10)), 0});
  EXPECT_NEAR(ante.versionDeg, 10, 1e-12);
  EXPECT_NEAR(ante.inclinationDeg, 0, 1e-12);
  const AxisAngles retro = axisAngles(f, {1, -std::tan(rad(7)), std::tan(rad(4))});
  EXPECT_NEAR(retro.versionDeg, -7, 1e-12);
  EXPECT_NEAR(retro.inclinationDeg, 4, 1e-12);
}

TEST(ScapularFrame, AMirroredLeftScapulaGivesTheSameAngles) {
  const ScapularFrame right = scapularFrame(rightScapula()), left = scapularFrame(mirrored(rightScapula()));
  EXPECT_NEAR(norm(left.anterior - Vec3{0, 1, 0}), 0, 1e-15);  // anterior stays anterior
  const Vec3 o{0.9, -0.2, 0.15};
  const AxisAngles a = axisAngles(right, o), b = axisAngles(left, {-o.x, o.y, o.z});
  EXPECT_NEAR(a.versionDeg, b.versionDeg, 1e-12);
  EXPECT_NEAR(a.inclinationDeg, b.inclinationDeg, 1e-12);
  EXPECT_LT(a.versionDeg, 0);  // pointing posteriorly: retroversion on both sides
}

// Any placement of the bone and any angles: angles -> axis -> angles is the identity, and the angles do not
// depend on where the bone lies.
TEST(ScapularFrame, AnglesRoundTripAndAreInvariantUnderRigidMotion) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(-80, 80), unit(-1, 1), offset(-500, 500);
  for (int i = 0; i < 2000; ++i) {
    const Vec3 k = normalized(Vec3{unit(rng), unit(rng), unit(rng)});
    const double theta = rad(180 * unit(rng));
    const Vec3 shift{offset(rng), offset(rng), offset(rng)};
    auto move = [&](const Vec3& v) {  // Rodrigues' rotation about k, then the shift
      return v * std::cos(theta) + cross(k, v) * std::sin(theta) + k * (dot(k, v) * (1 - std::cos(theta))) + shift;
    };
    auto turn = [&](const Vec3& v) { return move(v) - shift; };
    ScapulaLandmarks l = i % 2 ? rightScapula() : mirrored(rightScapula());
    for (ScapulaLandmark which : kScapulaLandmarks) *l[which] = move(*l[which]);
    const ScapularFrame f = scapularFrame(l);
    const AxisAngles want{angle(rng), angle(rng)};
    const Vec3 o = outwardAxisFor(f, want);
    const AxisAngles got = axisAngles(f, o);
    ASSERT_NEAR(got.versionDeg, want.versionDeg, 1e-9) << i;
    ASSERT_NEAR(got.inclinationDeg, want.inclinationDeg, 1e-9) << i;
    // The same axis in the unmoved frame.
    const ScapularFrame home = scapularFrame(i % 2 ? rightScapula() : mirrored(rightScapula()));
    const AxisAngles atHome = axisAngles(home, outwardAxisFor(home, want));
    ASSERT_NEAR(atHome.versionDeg, got.versionDeg, 1e-9);
    ASSERT_NEAR(dot(turn(outwardAxisFor(home, want)), o), 1, 1e-12);
  }
}

TEST(ScapularFrame, AnAimedReamerFeedsThroughTheGlenoidCentre) {
  const ScapularFrame f = scapularFrame(rightScapula());
  const Pose p = aimedReamerPose(f, {-8, 5}, 10);
  EXPECT_NEAR(norm(p.tip - f.origin), 10, 1e-12);
  EXPECT_NEAR(norm(cross(p.tip - f.origin, p.axis)), 0, 1e-12);  // the glenoid centre lies on the axis
  const AxisAngles a = axisAngles(f, p.axis * -1.0);
  EXPECT_NEAR(a.versionDeg, -8, 1e-12);
  EXPECT_NEAR(a.inclinationDeg, 5, 1e-12);
}

void expectRejected(const ScapulaLandmarks& l, const std::string& words) {
  try {
    scapularFrame(l);
    ADD_FAILURE() << "accepted; expected: " << words;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

TEST(ScapularFrame, LandmarksThatCannotDefineAFrameAreRejectedByName) {
  ScapulaLandmarks l = rightScapula();
  l[ScapulaLandmark::TrigonumScapulae].reset();
  expectRejected(l, "trigonum scapulae is not placed");
  l = rightScapula();
  l.side = BodySide::Unspecified;
  expectRejected(l, "side");
  l = rightScapula();
  l[ScapulaLandmark::InferiorAngle]->y = NAN;
  expectRejected(l, "inferior angle has a non-finite");
  l = rightScapula();
  l[ScapulaLandmark::InferiorAngle] = Vec3{1, 0, 1};
  expectRejected(l, "the trigonum scapulae and the inferior angle are");
  l = rightScapula();
  l[ScapulaLandmark::InferiorAngle] = Vec3{-100, 0, 3};  // nearly on the line through the other two
  expectRejected(l, "one line");
}

TEST(ScapularFrame, AxesAndAnglesOutsideTheirRangeAreRejected) {
  const ScapularFrame f = scapularFrame(rightScapula());
  EXPECT_THROW(axisAngles(f, {0, 0, 0}), std::invalid_argument);
  EXPECT_THROW(axisAngles(f, {NAN, 1, 0}), std::invalid_argument);
  EXPECT_THROW(axisAngles(f, {-1, 0.1, 0}), std::invalid_argument);  // medial
  EXPECT_THROW(axisAngles(f, {0, 1, 0}), std::invalid_argument);     // 90 degrees: undefined
  EXPECT_THROW(outwardAxisFor(f, {90, 0}), std::invalid_argument);
  EXPECT_THROW(outwardAxisFor(f, {0, NAN}), std::invalid_argument);
  EXPECT_THROW(aimedReamerPose(f, {0, 0}, INFINITY), std::invalid_argument);
}

// A CT bone knows its patient frame, and with it which side a scapula is.
TEST(ScapularFrame, TheSideFollowsFromAKnownPatientFrame) {
  ScapulaLandmarks l = rightScapula();  // RAS-like: lateral +x is the patient's right
  EXPECT_EQ(sideFromPatientFrame(PatientFrame::RAS, l), BodySide::Right);
  EXPECT_EQ(sideFromPatientFrame(PatientFrame::LPS, l), BodySide::Left);  // +x is the patient's left in LPS
  EXPECT_EQ(sideFromPatientFrame(PatientFrame::RAS, mirrored(l)), BodySide::Left);
  EXPECT_FALSE(sideFromPatientFrame(PatientFrame::Unspecified, l));
  l[ScapulaLandmark::TrigonumScapulae] = Vec3{50, -40, 0};  // the axis nearly sagittal: too close to tell
  EXPECT_FALSE(sideFromPatientFrame(PatientFrame::RAS, l));
  l[ScapulaLandmark::TrigonumScapulae].reset();
  EXPECT_FALSE(sideFromPatientFrame(PatientFrame::RAS, l));
}

TEST(LandmarkFiles, RoundTripCompleteAndPartialSets) {
  const ScapulaLandmarks full = rightScapula();
  EXPECT_EQ(parseLandmarksJson(landmarksToJson(full, "test"), "mem"), full);
  ScapulaLandmarks partial;
  partial[ScapulaLandmark::InferiorAngle] = Vec3{0.1, -2.5e-7, 1e5};
  const ScapulaLandmarks back = parseLandmarksJson(landmarksToJson(partial), "mem");
  EXPECT_EQ(back, partial);
  EXPECT_FALSE(back.complete());
  EXPECT_EQ(parseLandmarksJson(landmarksToJson(ScapulaLandmarks{}), "mem"), ScapulaLandmarks{});  // none placed
}

// The same files carry the reaming axis planned on the bone (docs/PLANNING.md), when there is one.
TEST(LandmarkFiles, APlannedAxisRoundTripsBesideTheLandmarks) {
  BonePlanning planning{rightScapula(), Pose{{60, 0, 0}, {-3, 0, 0}, 0}};
  const BonePlanning back = parsePlanningJson(planningToJson(planning, "test"), "mem");
  EXPECT_EQ(back.landmarks, planning.landmarks);
  ASSERT_TRUE(back.plannedAxis);
  EXPECT_EQ(back.plannedAxis->tip, planning.plannedAxis->tip);
  EXPECT_EQ(back.plannedAxis->axis, (Vec3{-1, 0, 0}));  // normalised on reading
  EXPECT_EQ(parseLandmarksJson(planningToJson(planning), "mem"), planning.landmarks);
  EXPECT_FALSE(parsePlanningJson(landmarksToJson(planning.landmarks), "mem").plannedAxis);
  for (const char* bad : {R"({"planned_axis": {"tip": [0, 0, 0]}})", R"({"planned_axis": {"tip": [0, 0, 0], "axis": [0, 0, 0]}})",
                          R"({"planned_axis": [1, 2, 3]})"})
    EXPECT_THROW(parsePlanningJson(bad, "plan.json"), InputError) << bad;
}

TEST(LandmarkFiles, DamagedFilesNameTheFileAndTheField) {
  const struct {
    const char* text;
    const char* words;
  } cases[] = {
      {"{", "not valid JSON"},
      {R"({"side": "left", "glenoid_centre": [1, 2, 1111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111]})",
       "not valid JSON"},  // a number beyond double (found by scripts/fuzz-readers.sh)
      {"[1, 2]", "must be a JSON object"},
      {R"({"side": "left", "glenoid_center": [1, 2, 3]})", "unknown key \"glenoid_center\""},
      {R"({"side": "up"})", "\"side\" must be"},
      {R"({"side": 3})", "\"side\" must be"},
      {R"({"side": "left", "glenoid_centre": [1, 2]})", "\"glenoid_centre\" must be an array of 3"},
      {R"({"side": "left", "inferior_angle": [1, "2", 3]})", "\"inferior_angle\" must be an array of 3"},
      {R"({"side": "left", "trigonum_scapulae": [1, 2, 1e300]})", "\"trigonum_scapulae\" has a value"},
  };
  for (const auto& c : cases) {
    try {
      parseLandmarksJson(c.text, "marks.json");
      ADD_FAILURE() << "accepted " << c.text;
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("marks.json"), std::string::npos) << what;
      EXPECT_NE(what.find(c.words), std::string::npos) << what;
    }
  }
  EXPECT_THROW(loadLandmarks("/nonexistent/marks.json"), InputError);
}

// The bundled landmarks lie on the bundled bone and give the native glenoid a version and inclination
// within the published spread (Churchill et al. 2001, 344 scapulae: on average about 1 deg of retroversion
// and 4 deg of superior inclination, each spread over roughly +-10 deg): a frame that came out mirrored or
// with its axes swapped would not.
TEST(LandmarkFiles, TheBundledLandmarksFitTheBundledScapula) {
  const DefaultBone bone = loadDefaultBone();
  const ScapulaLandmarks l = loadDefaultLandmarks();
  ASSERT_TRUE(l.complete());
  EXPECT_EQ(l.side, BodySide::Right);
  for (ScapulaLandmark which : kScapulaLandmarks) {
    double nearest = INFINITY;
    for (const Vec3& v : bone.mesh.vertices) nearest = std::min(nearest, norm(v - *l[which]));
    EXPECT_LT(nearest, 2.0) << displayName(which);
  }
  EXPECT_LT(norm(*l[ScapulaLandmark::GlenoidCentre] - bone.glenoid.centre), 1e-9);
  const ScapularFrame f = scapularFrame(l);
  EXPECT_GT(f.anterior.x, 0.5);  // OpenSim frame: +X anterior
  const AxisAngles native = axisAngles(f, bone.glenoid.outwardAxis);
  EXPECT_GT(native.versionDeg, -12);
  EXPECT_LT(native.versionDeg, 8);
  EXPECT_GT(native.inclinationDeg, -4);
  EXPECT_LT(native.inclinationDeg, 16);
}

}  // namespace
}  // namespace reamsim
