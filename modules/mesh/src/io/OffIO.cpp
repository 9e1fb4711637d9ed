// OFF (Geomview): optional [ST][C][N]OFF keyword, '#' comments, vertex lines with optional per-vertex
// extras matching the keyword, face lines "n i1 .. in" with an optional colour (1, 3 or 4 numbers).
#include <string_view>

#include "FileBytes.h"
#include "Formats.h"
#include "MeshBuilder.h"
#include "TextScanner.h"

namespace reamsim::io {
namespace {

struct Variant {
  int minExtra = 0;  // numbers after x y z on a vertex line
  int maxExtra = 0;
};

// Parses "OFF", "COFF", "NOFF", "CNOFF", "STOFF", "STCNOFF"...; false if `tok` is not an OFF keyword.
bool parseKeyword(std::string_view tok, Variant& v, TextScanner& s) {
  if (tok.size() < 3 || tok.substr(tok.size() - 3) != "OFF") return false;
  std::string_view prefix = tok.substr(0, tok.size() - 3);
  int st = 0, c = 0, n = 0;
  if (prefix.substr(0, 2) == "ST") st = 1, prefix.remove_prefix(2);
  if (!prefix.empty() && prefix[0] == 'C') c = 1, prefix.remove_prefix(1);
  if (!prefix.empty() && prefix[0] == 'N') n = 1, prefix.remove_prefix(1);
  if (!prefix.empty())
    s.fail("unsupported OFF variant " + quoteToken(tok) + " (4D, n-dimensional and binary OFF are not supported)");
  v.minExtra = 3 * n + 3 * c + 2 * st;
  v.maxExtra = v.minExtra + c;  // colour may be RGB or RGBA
  return true;
}

}  // namespace

RawMesh readOff(const std::string& path, std::string_view data, const StageProgress* progress) {
  TextScanner s(data, path, '#');
  RawMesh out;
  out.format = "off";
  s.collectCommentLines(&out.comments);
  Variant variant;
  std::string_view tok;
  if (!s.nextNonEmptyLine()) s.fail("the file has no content (only comments or blank lines)");
  s.token(tok);
  if (parseKeyword(tok, variant, s)) {
    if (!s.token(tok)) {
      if (!s.nextNonEmptyLine()) s.fail("unexpected end of file: missing the vertex/face counts line");
      s.token(tok);
    }
    if (tok == "BINARY") s.fail("binary OFF is not supported");
  }
  // tok is the vertex count (possibly on the keyword's line).
  const std::int64_t nv = s.parseInt(tok, "the vertex count");
  const std::int64_t nf = s.readInt("the face count");
  std::string_view edges;
  if (s.token(edges)) s.parseInt(edges, "the edge count");
  s.expectLineEnd("the counts");
  if (nv < 0 || nf < 0) s.fail("negative vertex or face count");
  if (nf == 0) s.fail("the file contains no triangles (face count is 0)");
  // Shortest possible lines: "0 0 0\n" and "3 0 1 2\n". Refuse counts the file cannot hold.
  const std::uint64_t available = data.size() - s.offsetAfterLine() + 1;
  const auto unv = static_cast<std::uint64_t>(nv), unf = static_cast<std::uint64_t>(nf);
  if (unv > available / 6 || unf > available / 8 || unv * 6 + unf * 8 > available)
    s.fail("header declares " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
           " faces, more than the remaining " + std::to_string(available - 1) + " bytes can hold (truncated file or wrong counts)");

  MeshBuilder b(path);
  b.reserve(static_cast<std::size_t>(nv), static_cast<std::size_t>(nf));
  b.watch(progress, [&s] { return s.offsetAfterLine(); }, data.size());
  for (std::int64_t i = 0; i < nv; ++i) {
    if (!s.nextNonEmptyLine())
      s.fail("unexpected end of file after " + std::to_string(i) + " of " + std::to_string(nv) + " vertices (file truncated?)");
    const std::string what = "vertex " + std::to_string(i);
    const double x = s.readDouble(what + " x"), y = s.readDouble(what + " y"), z = s.readDouble(what + " z");
    int extra = 0;
    while (extra < variant.maxExtra && s.token(tok)) {
      s.parseDouble(tok, what + " extra value");
      ++extra;
    }
    if (extra < variant.minExtra) s.fail(what + ": expected " + std::to_string(variant.minExtra) + " more values for this OFF variant");
    s.expectLineEnd("the vertex data");
    b.addVertex({x, y, z}, s.lineNumber());
  }
  std::vector<std::int64_t> poly;
  for (std::int64_t f = 0; f < nf; ++f) {
    if (!s.nextNonEmptyLine())
      s.fail("unexpected end of file after " + std::to_string(f) + " of " + std::to_string(nf) + " faces (file truncated?)");
    const std::string what = "face " + std::to_string(f);
    const std::int64_t n = s.readInt(what + " vertex count");
    if (n < 3) s.fail(what + " has only " + std::to_string(n) + " vertices (at least 3 needed)");
    poly.clear();
    for (std::int64_t k = 0; k < n; ++k) {
      if (!s.token(tok))
        s.fail(what + " declares " + std::to_string(n) + " vertices but the line has only " + std::to_string(k) + " indices");
      poly.push_back(s.parseInt(tok, what + " vertex index"));
    }
    int colour = 0;
    while (s.token(tok)) {
      s.parseDouble(tok, what + " colour value");
      ++colour;
    }
    if (colour == 2 || colour > 4)
      s.fail(what + ": " + std::to_string(colour) + " values after the indices (expected none or a colour of 1, 3 or 4)");
    b.addPolygon(poly, static_cast<std::uint64_t>(nv), s.lineNumber(), static_cast<std::size_t>(f));
  }
  if (s.nextNonEmptyLine()) s.fail("unexpected data after the last face");
  out.mesh = b.finish(out.notes);
  return out;
}

std::string writeOff(const TriangleMesh& mesh, const std::vector<std::string>& comments) {
  std::string out = "OFF\n";
  for (const std::string& c : commentLinesToWrite(comments)) out += "# " + c + "\n";
  out += std::to_string(mesh.vertices.size()) + ' ' + std::to_string(mesh.triangles.size()) + " 0\n";
  appendVertexAndTriangleLines(out, mesh);
  return out;
}

}  // namespace reamsim::io
