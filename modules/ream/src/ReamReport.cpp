#include "reamsim/ream/ReamReport.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <stdexcept>
#include <system_error>

#include "reamsim/ream/CutLogIO.h"
#include "reamsim/ream/ScapularFrame.h"

namespace reamsim {
namespace {

std::string escaped(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

// Fixed decimals in the C locale whatever the process's (std::to_chars does not look at the locale).
std::string fixed(double value, int decimals) {
  if (!std::isfinite(value)) return "–";
  char buffer[64];
  const auto r = std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::fixed, decimals);
  if (r.ec != std::errc()) return "–";  // beyond 60 digits: no bone measure is
  std::string s(buffer, r.ptr);
  if (s == "-0" || s.rfind("-0.", 0) == 0) {  // -0.00: a rounding to nothing keeps no sign
    bool zero = true;
    for (char c : s.substr(1))
      if (c != '0' && c != '.') zero = false;
    if (zero) s = s.substr(1);
  }
  return s;
}

std::string point(const Vec3& p) { return fixed(p.x, 2) + ", " + fixed(p.y, 2) + ", " + fixed(p.z, 2); }

std::string row(const std::string& label, const std::string& valueHtml) {
  return "<tr><th>" + escaped(label) + "</th><td>" + valueHtml + "</td></tr>\n";
}

std::string anglesText(const AxisAngles& a) {
  return fixed(a.versionDeg, 1) + "° (" +
         (a.versionDeg < 0 ? "retroversion" : a.versionDeg > 0 ? "anteversion" : "neutral") + "), " +
         fixed(a.inclinationDeg, 1) + "° (" +
         (a.inclinationDeg < 0 ? "inferior" : a.inclinationDeg > 0 ? "superior" : "neutral") + ")";
}

std::string reamerText(const ReamerSpec& r) {
  if (!r.meshFile.empty()) return escaped(r.name) + " (mesh " + escaped(r.meshFile) + ")";
  return escaped(r.name) + " (Ø " + fixed(r.diameterMm, 1) + " mm, " +
         (r.isFlat() ? std::string("flat") : "cap sphere R " + fixed(r.sphereRadiusMm, 1) + " mm") + ")";
}

ReportedGlenoidFace measuredFace(const BoneState& state, const Vec3& centre) {
  ReportedGlenoidFace r;
  try {
    r.face = measureGlenoidFace(state, centre);
  } catch (const std::invalid_argument& e) {
    r.problem = e.what();
  }
  return r;
}

}  // namespace

void addGlenoidFaces(ReamReportInput& in, const BoneState& opened, const BoneState& now) {
  const std::optional<Vec3>& centre = in.landmarks[ScapulaLandmark::GlenoidCentre];
  if (!centre) return;
  in.glenoidAsOpened = measuredFace(opened, *centre);
  in.glenoidNow = &now == &opened ? in.glenoidAsOpened : measuredFace(now, *centre);
}

void addSeat(ReamReportInput& in, const BoneState& now) {
  if (!in.reamerPose || !in.reamer.meshFile.empty()) return;
  in.seat = measureReamedSurface(now.toMesh(), in.reamer, *in.reamerPose);
}

std::string reamReportHtml(const ReamReportInput& in) {
  std::optional<ScapularFrame> frame;
  std::string frameProblem;
  try {
    frame = scapularFrame(in.landmarks);
  } catch (const std::invalid_argument& e) {
    frameProblem = e.what();
  }
  auto angles = [&](const Vec3& feedAxis) -> std::string {
    if (!frame) return "–";
    try {
      return anglesText(feedAxisAngles(*frame, feedAxis));
    } catch (const std::invalid_argument& e) {
      return escaped(e.what());
    }
  };
  auto glenoid = [&](const ReportedGlenoidFace& g) -> std::string {
    if (!g.face) return escaped(g.problem);
    return angles(g.face->outward * -1.0);  // its outward direction, read as a feed axis's opposite
  };
  // The planned axis's angles less the glenoid face's as opened: the correction the plan makes.
  auto correction = [&](const Vec3& feedAxis) -> std::string {
    if (!frame || !in.glenoidAsOpened.face) return {};
    try {
      const AxisAngles plan = feedAxisAngles(*frame, feedAxis);
      const AxisAngles face = axisAngles(*frame, in.glenoidAsOpened.face->outward);
      auto signedDeg = [](double d) { return (d > 0 ? "+" : "") + fixed(d, 1) + "°"; };
      return signedDeg(plan.versionDeg - face.versionDeg) + " of version, " +
             signedDeg(plan.inclinationDeg - face.inclinationDeg) + " of inclination";
    } catch (const std::invalid_argument&) {
      return {};
    }
  };

  std::string h;
  h += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" + escaped(in.title) +
       "</title>\n<style>\nbody{font-family:sans-serif;margin:2em;max-width:70em}\n"
       "table{border-collapse:collapse;margin:0.5em 0 1.5em}\nth,td{border:1px solid #bbb;padding:0.25em 0.6em;"
       "text-align:left}\ntd.n{text-align:right}\ntd.note{white-space:pre-wrap}\nimg{max-width:100%;border:1px solid #bbb}\n</style>\n</head>\n<body>\n";
  h += "<h1>" + escaped(in.title) + "</h1>\n";
  h += "<p>Written " + escaped(in.writtenUnixMs > 0 ? isoTimeUtc(in.writtenUnixMs) : std::string("(time not recorded)")) +
       " by " + escaped(in.writtenBy) + ".</p>\n";

  const double removed = in.volumeAtStartMm3 - in.volumeNowMm3;
  h += "<h2>Summary</h2>\n<table>\n";
  h += row("Bone", escaped(in.boneName));
  h += row("Source", escaped(in.boneSource.empty() ? std::string("–") : in.boneSource));
  h += row("Patient frame", escaped(toString(in.patientFrame)));
  h += row("Volume as opened", fixed(in.volumeAtStartMm3, 3) + " mm³");
  h += row("Volume now", fixed(in.volumeNowMm3, 3) + " mm³");
  h += row("Removed (as opened − now)", "<b>" + fixed(removed, 3) + " mm³</b>");
  h += row("Faces", std::to_string(in.facesAtStart) + " as opened, " + std::to_string(in.facesNow) + " now");
  std::size_t undone = 0;
  for (std::size_t i = 0; i < in.cuts.size() && i < in.undone.size(); ++i) undone += in.undone[i] ? 1 : 0;
  h += row("Cuts logged", std::to_string(in.cuts.size()) +
                              (undone ? " (" + std::to_string(undone) + " undone: not in the bone now)" : std::string()));
  h += row("Reamer", reamerText(in.reamer));
  if (in.reamerPose) {
    h += row("Reamer tip (mm)", point(in.reamerPose->tip));
    h += row("Reamer feed axis", point(in.reamerPose->axis));
    h += row("Reamer axis: version, inclination", angles(in.reamerPose->axis));
  }
  if (in.seat)
    h += row("Seat where the reamer is", fixed(100 * in.seat->seatedFraction, 1) + " % of the cutting face on bone; "
             "standoff from the ideal face " + fixed(in.seat->standoffMinMm, 4) + " to " +
             fixed(in.seat->standoffMaxMm, 4) + " mm, rms " + fixed(in.seat->standoffRmsMm, 4) +
             " mm (the reamer mesh's facets sag " + fixed(in.seat->facetSagMm, 4) + " mm)");
  if (in.glenoidAsOpened.face || !in.glenoidAsOpened.problem.empty()) {
    h += row("Glenoid face as opened: version, inclination", glenoid(in.glenoidAsOpened));
    h += row("Glenoid face now: version, inclination", glenoid(in.glenoidNow));
  }
  if (in.plannedAxis) {
    h += row("Planned axis: version, inclination", angles(in.plannedAxis->axis));
    if (const std::string c = correction(in.plannedAxis->axis); !c.empty())
      h += row("Planned axis from the glenoid face as opened", c);
    h += row("Planned axis through (mm)", point(in.plannedAxis->tip));
    if (in.reamerPose)
      h += row("Reamer axis off the plan", fixed(axisDeviationDeg(in.plannedAxis->axis, in.reamerPose->axis), 1) + "°");
  }
  h += "</table>\n";

  h += "<h2>Scapular landmarks</h2>\n";
  if (frame) {
    h += "<table>\n";
    h += row("Side", escaped(toString(in.landmarks.side)));
    for (ScapulaLandmark which : kScapulaLandmarks)
      h += row(displayName(which), point(*in.landmarks[which]) + " mm");
    h += "</table>\n<p>Version and inclination are the angles of the reamer axis (out of the glenoid) in the "
         "transverse and scapular planes of the scapular frame: lateral from the trigonum scapulae to the glenoid "
         "centre, superior in the plane of the three landmarks (docs/PLANNING.md). The glenoid face's are those of "
         "the bone's surface within " + fixed(GlenoidFaceOptions{}.radiusMm, 0) + " mm of the glenoid centre (the "
         "plane of that piece's rim).</p>\n";
  } else {
    h += "<p>No scapular frame: " + escaped(frameProblem) + ". Version and inclination are not given.</p>\n";
  }

  h += "<h2>Cuts</h2>\n";
  if (in.cuts.empty()) {
    h += "<p>No cut was logged.</p>\n";
  } else {
    const bool anyNote = std::any_of(in.cuts.begin(), in.cuts.end(), [](const CutLogEntry& e) { return !e.note.empty(); });
    h += "<table>\n<tr><th>step</th><th>time (UTC)</th><th>removed mm³</th><th>cumulative mm³</th><th>faces</th>"
         "<th>cut ms</th><th>reamer</th><th>version, inclination</th>" +
         std::string(in.plannedAxis ? "<th>off the plan</th>" : "") + (anyNote ? "<th>note</th>" : "") + "</tr>\n";
    for (std::size_t i = 0; i < in.cuts.size(); ++i) {
      const CutLogEntry& e = in.cuts[i];
      const bool wasUndone = i < in.undone.size() && in.undone[i];
      h += "<tr><td class=\"n\">" + std::to_string(e.stepIndex) + (wasUndone ? " (undone)" : "") + "</td><td>" +
           escaped(isoTimeUtc(e.timeUnixMs)) + "</td><td class=\"n\">" + fixed(e.removedMm3, 3) +
           "</td><td class=\"n\">" + fixed(e.cumulativeMm3, 3) + "</td><td class=\"n\">" + std::to_string(e.faces) +
           "</td><td class=\"n\">" + fixed(e.cutMs, 1) + "</td><td>" + escaped(e.reamer) + "</td><td>" +
           angles(e.pose.axis) + "</td>" +
           (in.plannedAxis ? "<td class=\"n\">" + fixed(axisDeviationDeg(in.plannedAxis->axis, e.pose.axis), 1) + "°</td>"
                           : std::string()) +
           (anyNote ? "<td class=\"note\">" + escaped(e.note) + "</td>" : std::string()) + "</tr>\n";
    }
    h += "</table>\n";
  }
  if (!in.pngBase64.empty()) {
    for (char c : in.pngBase64)
      if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '+' || c == '/' || c == '='))
        throw std::invalid_argument("the picture for the report is not base64");
    h += "<h2>View</h2>\n<img alt=\"the bone and the reamer as shown\" src=\"data:image/png;base64," + in.pngBase64 +
         "\">\n";
  }
  h += "</body>\n</html>\n";
  return h;
}

}  // namespace reamsim
