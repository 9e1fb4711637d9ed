// Wavefront OBJ: 'v' and 'f' statements; texture/normal data and grouping/material statements are ignored.
#include <array>
#include <string_view>

#include "FileBytes.h"
#include "Formats.h"
#include "MeshBuilder.h"
#include "TextScanner.h"

namespace reamsim::io {
namespace {

// Statements that are valid OBJ but carry nothing a triangle mesh needs.
bool isIgnoredStatement(std::string_view k) {
  static constexpr std::array<std::string_view, 33> kIgnored = {
      "vt",    "vn",    "vp",    "g",      "o",    "s",      "usemtl",   "mtllib",    "l",         "p",    "cstype",
      "deg",   "bmat",  "step",  "curv",   "curv2", "surf",  "parm",     "trim",      "hole",      "scrv", "sp",
      "end",   "con",   "mg",    "lod",    "usemap", "maplib", "shadow_obj", "trace_obj", "ctech", "stech", "bevel"};
  for (std::string_view s : kIgnored)
    if (k == s) return true;
  return k == "c_interp" || k == "d_interp";
}

}  // namespace

RawMesh readObj(const std::string& path, std::string_view data, const StageProgress* progress) {
  TextScanner s(data, path, '#');
  MeshBuilder b(path, 1);
  b.watch(progress, [&s] { return s.offsetAfterLine(); }, data.size());
  RawMesh out;
  out.format = "obj";
  s.collectCommentLines(&out.comments);
  std::vector<std::int64_t> poly;
  std::size_t faces = 0;
  std::string_view key;
  while (s.nextLine()) {
    b.step();
    if (!s.token(key)) continue;
    if (key == "v") {
      const double x = s.readDouble("vertex x"), y = s.readDouble("vertex y"), z = s.readDouble("vertex z");
      // Optional w, or r g b (a common extension): up to 4 more numbers.
      std::string_view extra;
      for (int i = 0; i < 4 && s.token(extra); ++i) s.parseDouble(extra, "optional vertex value");
      s.expectLineEnd("vertex data");
      b.addVertex({x, y, z}, s.lineNumber());
    } else if (key == "f" || key == "fo") {
      poly.clear();
      const std::int64_t count = static_cast<std::int64_t>(b.vertexCount());
      const std::string face = "face " + std::to_string(faces + 1);
      std::string_view tok;
      while (s.token(tok)) {
        // v, v/vt, v/vt/vn or v//vn: check every part's syntax, use only v.
        std::string_view parts[3];
        std::size_t nparts = 0;
        std::size_t start = 0;
        for (;;) {
          const std::size_t slash = tok.find('/', start);
          if (nparts == 3) s.fail(face + ": malformed vertex reference " + quoteToken(tok));
          parts[nparts++] = tok.substr(start, slash == std::string_view::npos ? std::string_view::npos : slash - start);
          if (slash == std::string_view::npos) break;
          start = slash + 1;
        }
        for (std::size_t p = 0; p < nparts; ++p) {
          std::int64_t dummy = 0;
          const bool optionalEmpty = parts[p].empty() && p == 1 && nparts == 3;  // v//vn
          if (!optionalEmpty && !parseIntToken(parts[p], dummy))
            s.fail(face + ": malformed vertex reference " + quoteToken(tok) + " (expected v, v/vt, v/vt/vn or v//vn)");
        }
        std::int64_t v = 0;
        parseIntToken(parts[0], v);
        if (v == 0) s.fail(face + ": vertex index 0 is invalid (OBJ indices start at 1; negative ones count back)");
        const std::int64_t resolved = v > 0 ? v - 1 : count + v;
        if (resolved < 0 || resolved >= count)
          s.fail(face + ": vertex index " + std::to_string(v) + " is out of range (" + std::to_string(count) +
                 " vertices defined so far)");
        poly.push_back(resolved);
      }
      b.addPolygon(poly, static_cast<std::uint64_t>(count), s.lineNumber(), faces);
      ++faces;
    } else if (!isIgnoredStatement(key)) {
      s.fail("unknown OBJ statement " + quoteToken(key));
    }
  }
  out.mesh = b.finish(out.notes);
  return out;
}

std::string writeObj(const TriangleMesh& mesh, const std::vector<std::string>& comments) {
  std::string out;
  for (const std::string& c : commentLinesToWrite(comments)) out += "# " + c + "\n";
  for (const Vec3& p : mesh.vertices) {
    out += "v ";
    appendTriple(out, p.x, p.y, p.z);
    out += '\n';
  }
  for (const Triangle& t : mesh.triangles)
    out += "f " + std::to_string(t[0] + 1) + ' ' + std::to_string(t[1] + 1) + ' ' + std::to_string(t[2] + 1) + '\n';
  return out;
}

}  // namespace reamsim::io
