// The reaming report (reamsim/ream/ReamReport.h): what it says, escaped, with and without landmarks.
#include <gtest/gtest.h>

#include "reamsim/ream/DefaultCase.h"
#include "reamsim/ream/ReamReport.h"
#include "reamsim/ream/ScapularFrame.h"

namespace reamsim {
namespace {

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

ReamReportInput twoCuts() {
  ReamReportInput in;
  in.boneName = "scapula <left> & \"copy\"";
  in.boneSource = "bundled";
  in.volumeAtStartMm3 = 63000.25;
  in.volumeNowMm3 = 62800.125;
  in.facesAtStart = 14998;
  in.facesNow = 15200;
  in.reamer.name = "glenoid-36-R30";
  in.reamer.diameterMm = 36;
  in.reamer.sphereRadiusMm = 30;
  Pose pose;
  pose.axis = {-0.6058700515736587, 0.03791606437579332, -0.794659582883377};  // the bundled glenoid's feed
  in.reamerPose = pose;
  for (int i = 0; i < 2; ++i) {
    CutLogEntry e;
    e.stepIndex = std::size_t(3 + i);
    e.timeUnixMs = 1764000000000 + i;
    e.pose = pose;
    e.removedMm3 = 100.0625;
    e.cumulativeMm3 = 100.0625 * (i + 1);
    e.faces = 15100 + std::size_t(i);
    e.reamer = "glenoid-36-R30";
    in.cuts.push_back(e);
  }
  return in;
}

TEST(ReamReport, SaysWhatWasRemovedCutByCutAndEscapesNames) {
  const std::string html = reamReportHtml(twoCuts());
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(html.find("scapula &lt;left&gt; &amp; &quot;copy&quot;"), std::string::npos);
  EXPECT_EQ(html.find("<left>"), std::string::npos);
  EXPECT_NE(html.find("<b>200.125 mm³</b>"), std::string::npos);  // 63000.25 − 62800.125
  EXPECT_NE(html.find("14998 as opened, 15200 now"), std::string::npos);
  EXPECT_NE(html.find("Ø 36.0 mm, cap sphere R 30.0 mm"), std::string::npos);
  EXPECT_EQ(count(html, "<tr><td class=\"n\">"), 2u);  // one row per cut
  EXPECT_NE(html.find("<td class=\"n\">200.125</td>"), std::string::npos);
  EXPECT_NE(html.find("2025-11-24T16:00:00.001Z"), std::string::npos);
  EXPECT_NE(html.find("No scapular frame: the glenoid centre is not placed"), std::string::npos);
  EXPECT_EQ(html.find("<img"), std::string::npos);
  EXPECT_EQ(count(html, "<table>"), count(html, "</table>"));
  EXPECT_EQ(count(html, "<tr>"), count(html, "</tr>"));
  EXPECT_EQ(html.find("<th>note</th>"), std::string::npos);  // no cut has a note: no column
}

// A cut's note (an annotation) gets a column, escaped, when any cut has one.
TEST(ReamReport, ShowsTheCutsNotesEscaped) {
  ReamReportInput in = twoCuts();
  in.cuts[1].note = "tilted <5°> & \"re-seated\"\nthen fed";
  const std::string html = reamReportHtml(in);
  EXPECT_NE(html.find("<th>note</th>"), std::string::npos);
  EXPECT_EQ(count(html, "<td class=\"note\">"), 2u);  // the row without a note has an empty cell
  EXPECT_NE(html.find("<td class=\"note\">tilted &lt;5°&gt; &amp; &quot;re-seated&quot;\nthen fed</td>"), std::string::npos);
  EXPECT_EQ(count(html, "<tr>"), count(html, "</tr>"));
}

TEST(ReamReport, GivesTheAxisVersionAndInclinationWithLandmarks) {
  ReamReportInput in = twoCuts();
  in.landmarks = loadDefaultLandmarks();
  in.pngBase64 = "iVBORw0KGgo=";
  const std::string html = reamReportHtml(in);
  const AxisAngles a = axisAngles(scapularFrame(in.landmarks), in.reamerPose->axis * -1.0);
  ASSERT_LT(a.versionDeg, 0);
  char expected[96];
  std::snprintf(expected, sizeof expected, "%.1f° (retroversion), %.1f° (superior)", a.versionDeg, a.inclinationDeg);
  EXPECT_EQ(count(html, expected), 3u) << expected;  // the reamer now and both cuts
  EXPECT_NE(html.find("trigonum scapulae"), std::string::npos);
  EXPECT_NE(html.find("src=\"data:image/png;base64,iVBORw0KGgo=\""), std::string::npos);
  in.pngBase64 = "not base64 <script>";
  EXPECT_THROW(reamReportHtml(in), std::invalid_argument);
}

// The glenoid face as opened and now, and what the planned axis corrects of it; a centre off the bone is named.
TEST(ReamReport, GivesTheGlenoidFaceBeforeAndAfterAndThePlansCorrection) {
  const DefaultBone bone = loadDefaultBone();
  const BoneState opened = BoneState::fromMesh(bone.mesh);
  ReamReportInput in = twoCuts();
  in.landmarks = loadDefaultLandmarks();
  const ScapularFrame frame = scapularFrame(in.landmarks);
  const AxisAngles aimed{-10, 5};
  in.plannedAxis = Pose{frame.origin, outwardAxisFor(frame, aimed) * -1.0, 0};
  addGlenoidFaces(in, opened, opened);
  ASSERT_TRUE(in.glenoidAsOpened.face && in.glenoidNow.face);
  const AxisAngles face = axisAngles(frame, in.glenoidAsOpened.face->outward);
  const std::string html = reamReportHtml(in);
  char expected[160];
  std::snprintf(expected, sizeof expected, "%.1f° (retroversion), %.1f° (superior)", face.versionDeg, face.inclinationDeg);
  EXPECT_EQ(count(html, expected), 2u) << expected;  // as opened and now: the same state
  std::snprintf(expected, sizeof expected, "%+.1f° of version, %+.1f° of inclination", -10 - face.versionDeg,
                5 - face.inclinationDeg);
  EXPECT_NE(html.find(expected), std::string::npos) << expected;
  // The seat at the reamer's pose: its row when measured, none for a reamer read from a mesh.
  EXPECT_EQ(html.find("Seat where the reamer"), std::string::npos);
  addSeat(in, opened);
  ASSERT_TRUE(in.seat);
  EXPECT_NE(reamReportHtml(in).find("Seat where the reamer is</th><td>0.0 % of the cutting face on bone"), std::string::npos);
  ReamReportInput meshReamer = twoCuts();
  meshReamer.reamer.meshFile = "reamer.stl";
  addSeat(meshReamer, opened);
  EXPECT_FALSE(meshReamer.seat);
  // Without the glenoid centre: no glenoid rows at all; with one off the bone: the reason, in both rows.
  ReamReportInput none = twoCuts();
  addGlenoidFaces(none, opened, opened);
  EXPECT_EQ(reamReportHtml(none).find("Glenoid face"), std::string::npos);
  in.landmarks[ScapulaLandmark::GlenoidCentre] = Vec3{500, 500, 500};
  addGlenoidFaces(in, opened, opened);
  EXPECT_EQ(count(reamReportHtml(in), "no bone surface lies within 10 mm of the glenoid centre"), 2u);
}

}  // namespace
}  // namespace reamsim
