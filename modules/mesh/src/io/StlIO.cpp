// STL: binary (detected by the size rule 84 + 50 n, not by the "solid" keyword) and ASCII.
#include <cstdint>
#include <limits>

#include "ByteReader.h"
#include "FileBytes.h"
#include "Formats.h"
#include "MeshBuilder.h"
#include "TextScanner.h"
#include "reamsim/mesh/MeshError.h"

namespace reamsim::io {
namespace {

constexpr std::size_t kHeader = 84;
constexpr std::size_t kRecord = 50;
constexpr const char* kStlHeaderMark = "ReamSim binary STL";

bool looksLikeAsciiStl(std::string_view data) {
  std::size_t i = 0;
  while (i < data.size() && (data[i] == ' ' || data[i] == '\t' || data[i] == '\r' || data[i] == '\n')) ++i;
  if (data.compare(i, 5, "solid") != 0) return false;
  // Binary files may start with "solid" too; text never contains NUL or most control bytes.
  for (char ch : data) {
    const auto c = static_cast<unsigned char>(ch);
    if (c < 0x20 && c != '\n' && c != '\r' && c != '\t' && c != '\f' && c != '\v') return false;
  }
  return true;
}

// "ReamSim binary STL", then the comments after "written by ReamSim" that fit in the 80 bytes, each ended
// by a line break (the reader keeps only ended lines); spaces after. Other programs ignore the header.
std::string binaryHeader(const std::vector<std::string>& comments, std::vector<std::string>* kept = nullptr) {
  std::string header = kStlHeaderMark;
  const std::vector<std::string> lines = commentLinesToWrite(comments);
  for (std::size_t i = 1; i < lines.size(); ++i)
    if (header.size() + 1 + lines[i].size() + 1 <= kHeader - 4) {  // with its own break and the last one
      header += '\n' + lines[i];
      if (kept) kept->push_back(lines[i]);
    }
  header += '\n';
  header.resize(kHeader - 4, ' ');
  return header;
}

// The comments of a header ReamSim wrote ("written by ReamSim" for the mark itself); none for others.
std::vector<std::string> commentsOfHeader(std::string_view header) {
  const std::string_view mark = kStlHeaderMark;
  if (header.substr(0, mark.size()) != mark || header.size() == mark.size() || header[mark.size()] != '\n') return {};
  std::vector<std::string> out{kWrittenByComment};
  std::string_view rest = header.substr(mark.size() + 1);
  for (std::size_t end; (end = rest.find('\n')) != std::string_view::npos; rest.remove_prefix(end + 1))
    out.emplace_back(rest.substr(0, end));
  return out;
}

// ASCII STL has no comment lines, only the solid's name, which readers show or ignore: ReamSim names its solid
// "reamsim" followed by its comment lines, each after a tab ("solid reamsim<TAB>written by ReamSim<TAB>…").
std::string asciiSolidName(const std::vector<std::string>& comments) {
  std::string name = "reamsim";
  for (std::string line : commentLinesToWrite(comments)) {
    for (char& ch : line)
      if (ch == '\t') ch = ' ';
    name += '\t' + line;
  }
  return name;
}

// The comments of a solid name ReamSim wrote (asciiSolidName); none for others, or for "reamsim" alone (the
// name before session 52).
std::vector<std::string> commentsOfSolidName(std::string_view name) {
  constexpr std::string_view mark = "reamsim\t";
  if (name.substr(0, mark.size()) != mark) return {};
  std::vector<std::string> out;
  std::string_view rest = name.substr(mark.size());
  for (std::size_t end; (end = rest.find('\t')) != std::string_view::npos; rest.remove_prefix(end + 1))
    out.emplace_back(rest.substr(0, end));
  out.emplace_back(rest);
  return out;
}

RawMesh readBinary(const std::string& path, std::string_view data, const StageProgress* progress) {
  if (data.size() < kHeader)
    throw InputError(path, "not a valid STL file: too small for a binary STL header (" + std::to_string(data.size()) +
                               " bytes, need 84) and not ASCII STL");
  ByteReader in(data, path, false);
  in.skip(80, "header");
  const std::uint32_t count = in.read<std::uint32_t>("triangle count");
  const std::uint64_t expected = kHeader + kRecord * static_cast<std::uint64_t>(count);
  if (count == 0) throw InputError(path, "binary STL header says the file contains no triangles");
  if (expected > data.size())
    throw InputError(path, "binary STL header claims " + std::to_string(count) + " triangles (" +
                               std::to_string(expected) + " bytes) but the file has only " +
                               std::to_string(data.size()) + " bytes (truncated or not an STL file)");
  if (expected < data.size())
    throw InputError(path, "binary STL header claims " + std::to_string(count) + " triangles (" +
                               std::to_string(expected) + " bytes) but the file has " + std::to_string(data.size()) +
                               " bytes (extra data after the last triangle, or not an STL file)");
  RawMesh out;
  out.format = "stl-binary";
  out.comments = commentsOfHeader(data.substr(0, 80));
  MeshBuilder b(path);
  b.reserve(count, count);  // justified: the file holds all records
  b.watch(progress, [&in] { return in.offset(); }, data.size());
  const std::string what = "triangle data";  // sizes were checked above; reads cannot fail
  for (std::uint32_t t = 0; t < count; ++t) {
    in.skip(12, what);  // normal: recomputed by consumers, never trusted
    std::uint32_t idx[3];
    for (int c = 0; c < 3; ++c) {
      const float x = in.read<float>(what), y = in.read<float>(what), z = in.read<float>(what);
      idx[c] = b.addWeldedVertex({x, y, z}, 0,
                                 [&] { return "triangle " + std::to_string(t) + " corner " + std::to_string(c); });
    }
    in.skip(2, what);  // attribute byte count
    b.addTriangle(idx[0], idx[1], idx[2]);
  }
  out.mesh = b.finish(out.notes);
  return out;
}

RawMesh readAscii(const std::string& path, std::string_view data, const StageProgress* progress) {
  TextScanner s(data, path);
  MeshBuilder b(path);
  b.watch(progress, [&s] { return s.offsetAfterLine(); }, data.size());
  RawMesh out;
  out.format = "stl-ascii";
  std::string_view tok;
  bool inSolid = false;
  bool sawEnd = false;
  std::size_t facet = 0;
  std::vector<std::int64_t> loop;
  const auto expectWord = [&](const char* word, const char* context) {
    std::string_view t;
    if (!s.tokenAcrossLines(t)) s.fail(std::string("unexpected end of file: expected '") + word + "' " + context + " (file truncated?)");
    if (t != word) s.fail("expected '" + std::string(word) + "' " + context + ", found " + quoteToken(t));
  };
  while (s.tokenAcrossLines(tok)) {
    if (!inSolid) {
      if (tok != "solid") s.fail("expected 'solid', found " + quoteToken(tok));
      const std::string_view name = s.restOfLine();
      if (out.comments.empty()) out.comments = commentsOfSolidName(name);  // the first solid's
      inSolid = true;
      sawEnd = false;
      continue;
    }
    if (tok == "endsolid") {
      s.restOfLine();
      inSolid = false;
      sawEnd = true;
      continue;
    }
    if (tok != "facet") s.fail("expected 'facet' or 'endsolid', found " + quoteToken(tok));
    const std::string ctx = "in facet " + std::to_string(facet);
    expectWord("normal", ctx.c_str());
    for (int i = 0; i < 3; ++i) s.readDouble("facet normal component");
    expectWord("outer", ctx.c_str());
    expectWord("loop", ctx.c_str());
    loop.clear();
    long loopLine = s.lineNumber();
    for (;;) {
      if (!s.tokenAcrossLines(tok)) s.fail("unexpected end of file " + ctx + " (file truncated?)");
      if (tok == "endloop") break;
      if (tok != "vertex") s.fail("expected 'vertex' or 'endloop' " + ctx + ", found " + quoteToken(tok));
      const double x = s.readDouble("vertex x"), y = s.readDouble("vertex y"), z = s.readDouble("vertex z");
      s.expectLineEnd("vertex coordinates");
      loop.push_back(b.addWeldedVertex({x, y, z}, s.lineNumber(), [&] {
        return "facet " + std::to_string(facet) + " vertex " + std::to_string(loop.size());
      }));
      loopLine = s.lineNumber();
    }
    expectWord("endfacet", ctx.c_str());
    b.addPolygon(loop, b.vertexCount(), loopLine, facet);
    ++facet;
  }
  if (!inSolid && !sawEnd) s.fail("the file is empty (no 'solid')");
  if (inSolid) {
    if (facet == 0) s.fail("unexpected end of file: missing 'endsolid' (file truncated?)");
    out.notes.push_back("ASCII STL: 'endsolid' is missing at the end (file may be truncated)");
  }
  out.mesh = b.finish(out.notes);
  return out;
}

Vec3 unitNormal(const TriangleMesh& m, const Triangle& t) {
  return normalized(cross(m.vertices[t[1]] - m.vertices[t[0]], m.vertices[t[2]] - m.vertices[t[0]]));
}

}  // namespace

RawMesh readStl(const std::string& path, std::string_view data, const StageProgress* progress) {
  if (data.size() >= kHeader) {
    std::uint32_t count = 0;
    ByteReader in(data, path, false);
    in.skip(80, "header");
    count = in.read<std::uint32_t>("triangle count");
    if (kHeader + kRecord * static_cast<std::uint64_t>(count) == data.size()) return readBinary(path, data, progress);
  }
  if (looksLikeAsciiStl(data)) return readAscii(path, data, progress);
  return readBinary(path, data, progress);
}

std::string writeStl(const TriangleMesh& mesh, const std::string& path, bool binary,
                     const std::vector<std::string>& comments) {
  std::string out;
  if (binary) {
    if (mesh.triangles.size() > std::numeric_limits<std::uint32_t>::max())
      throw InputError(path, "too many triangles for binary STL");
    out.reserve(kHeader + kRecord * mesh.triangles.size());
    std::string header = binaryHeader(comments);
    out += header;
    appendLittleEndian(out, static_cast<std::uint32_t>(mesh.triangles.size()));
    for (const Triangle& t : mesh.triangles) {
      const Vec3 n = unitNormal(mesh, t);
      for (double v : {n.x, n.y, n.z}) appendLittleEndian(out, static_cast<float>(v));
      for (std::uint32_t i : t)
        for (double v : {mesh.vertices[i].x, mesh.vertices[i].y, mesh.vertices[i].z})
          appendLittleEndian(out, static_cast<float>(v));
      appendLittleEndian(out, std::uint16_t{0});
    }
    return out;
  }
  out += "solid " + asciiSolidName(comments) + "\n";
  for (const Triangle& t : mesh.triangles) {
    const Vec3 n = unitNormal(mesh, t);
    out += "  facet normal ";
    appendTriple(out, n.x, n.y, n.z);
    out += "\n    outer loop\n";
    for (std::uint32_t i : t) {
      out += "      vertex ";
      appendTriple(out, mesh.vertices[i].x, mesh.vertices[i].y, mesh.vertices[i].z);
      out += '\n';
    }
    out += "    endloop\n  endfacet\n";
  }
  out += "endsolid reamsim\n";
  return out;
}

std::vector<std::string> binaryStlCommentsKept(const std::vector<std::string>& comments) {
  std::vector<std::string> kept;
  binaryHeader(comments, &kept);
  return kept;
}

}  // namespace reamsim::io
