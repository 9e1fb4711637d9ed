// PLY: ASCII and binary little/big endian. Reads x/y/z of the 'vertex' element (any numeric type) and the
// 'vertex_indices' (or 'vertex_index') list of the 'face' element; every other element and property is
// skipped by its declared type.
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include "ByteReader.h"
#include "FileBytes.h"
#include "Formats.h"
#include "MeshBuilder.h"
#include "TextScanner.h"
#include "reamsim/mesh/MeshError.h"

namespace reamsim::io {
namespace {

enum class Type { Int8, UInt8, Int16, UInt16, Int32, UInt32, Int64, UInt64, Float32, Float64 };

std::optional<Type> parseType(std::string_view s) {
  if (s == "char" || s == "int8") return Type::Int8;
  if (s == "uchar" || s == "uint8") return Type::UInt8;
  if (s == "short" || s == "int16") return Type::Int16;
  if (s == "ushort" || s == "uint16") return Type::UInt16;
  if (s == "int" || s == "int32") return Type::Int32;
  if (s == "uint" || s == "uint32") return Type::UInt32;
  if (s == "int64" || s == "long") return Type::Int64;
  if (s == "uint64" || s == "ulong") return Type::UInt64;
  if (s == "float" || s == "float32") return Type::Float32;
  if (s == "double" || s == "float64") return Type::Float64;
  return std::nullopt;
}

std::size_t sizeOf(Type t) {
  switch (t) {
    case Type::Int8: case Type::UInt8: return 1;
    case Type::Int16: case Type::UInt16: return 2;
    case Type::Int32: case Type::UInt32: case Type::Float32: return 4;
    default: return 8;
  }
}

bool isInteger(Type t) { return t != Type::Float32 && t != Type::Float64; }

struct Property {
  std::string name;
  Type type = Type::Float32;
  bool isList = false;
  Type countType = Type::UInt8;
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> props;
  long line = 0;
};

enum class Encoding { Ascii, BinaryLE, BinaryBE };

struct Header {
  Encoding encoding = Encoding::Ascii;
  std::vector<Element> elements;
  std::size_t dataOffset = 0;
  long lastLine = 0;
  std::vector<std::string> comments;  // text of the 'comment' lines, in order
};

Header parseHeader(const std::string& path, std::string_view data) {
  TextScanner s(data, path);
  Header h;
  std::string_view tok;
  if (!s.nextLine() || !s.token(tok) || tok != "ply") s.fail("not a PLY file (first line must be 'ply')");
  s.expectLineEnd("'ply'");
  bool haveFormat = false;
  for (;;) {
    if (!s.nextLine()) s.fail("unexpected end of file in the PLY header (no 'end_header')");
    if (!s.token(tok)) continue;
    if (tok == "comment") {
      h.comments.emplace_back(s.restOfLine());
      continue;
    }
    if (tok == "obj_info") continue;
    if (tok == "end_header") {
      s.expectLineEnd("'end_header'");
      break;
    }
    if (tok == "format") {
      const std::string_view f = s.requireToken("the format name");
      if (f == "ascii") h.encoding = Encoding::Ascii;
      else if (f == "binary_little_endian") h.encoding = Encoding::BinaryLE;
      else if (f == "binary_big_endian") h.encoding = Encoding::BinaryBE;
      else s.fail("unknown PLY format " + quoteToken(f));
      const std::string_view version = s.requireToken("the format version");
      if (version != "1.0" && version != "1") s.fail("unsupported PLY version " + quoteToken(version));
      s.expectLineEnd("the format line");
      haveFormat = true;
    } else if (tok == "element") {
      Element e;
      e.name = std::string(s.requireToken("the element name"));
      const std::int64_t n = s.readInt("the element count");
      if (n < 0) s.fail("negative count for element '" + e.name + "'");
      e.count = static_cast<std::uint64_t>(n);
      e.line = s.lineNumber();
      s.expectLineEnd("the element declaration");
      for (const Element& other : h.elements)
        if (other.name == e.name) s.fail("element '" + e.name + "' is declared twice");
      h.elements.push_back(std::move(e));
    } else if (tok == "property") {
      if (h.elements.empty()) s.fail("'property' before any 'element'");
      Property p;
      std::string_view t = s.requireToken("the property type");
      if (t == "list") {
        p.isList = true;
        const std::string_view ct = s.requireToken("the list count type");
        const auto c = parseType(ct);
        if (!c || !isInteger(*c)) s.fail("invalid list count type " + quoteToken(ct));
        p.countType = *c;
        t = s.requireToken("the list item type");
      }
      const auto type = parseType(t);
      if (!type) s.fail("unknown property type " + quoteToken(t));
      p.type = *type;
      p.name = std::string(s.requireToken("the property name"));
      s.expectLineEnd("the property declaration");
      h.elements.back().props.push_back(std::move(p));
    } else {
      s.fail("unknown PLY header keyword " + quoteToken(tok));
    }
  }
  if (!haveFormat) s.fail("the PLY header has no 'format' line");
  h.dataOffset = s.offsetAfterLine();
  h.lastLine = s.lineNumber();
  return h;
}

// Where the mesh data sits inside the elements.
struct Layout {
  const Element* vertex = nullptr;
  int xyz[3] = {-1, -1, -1};
  const Element* face = nullptr;
  int indices = -1;
};

Layout findLayout(const std::string& path, const Header& h) {
  Layout l;
  for (const Element& e : h.elements) {
    if (e.name == "vertex") {
      l.vertex = &e;
      for (std::size_t i = 0; i < e.props.size(); ++i) {
        const std::string& n = e.props[i].name;
        const int axis = n == "x" ? 0 : n == "y" ? 1 : n == "z" ? 2 : -1;
        if (axis < 0) continue;
        if (e.props[i].isList) throw InputError(path, e.line, "vertex property '" + n + "' must not be a list");
        l.xyz[axis] = static_cast<int>(i);
      }
      for (int a = 0; a < 3; ++a)
        if (l.xyz[a] < 0)
          throw InputError(path, e.line, std::string("the vertex element has no '") + "xyz"[a] + "' property");
    } else if (e.name == "face") {
      l.face = &e;
      for (std::size_t i = 0; i < e.props.size(); ++i)
        if (e.props[i].isList && (e.props[i].name == "vertex_indices" || e.props[i].name == "vertex_index"))
          l.indices = static_cast<int>(i);
      if (l.indices < 0)
        throw InputError(path, e.line, "the face element has no 'vertex_indices' (or 'vertex_index') list property");
    }
  }
  if (!l.vertex) throw InputError(path, "the PLY header declares no 'vertex' element");
  if (!l.face || l.face->count == 0) throw InputError(path, "the file contains no triangles (no faces)");
  return l;
}

// The fewest bytes (binary) or characters (ASCII: one digit and one separator per value) an element can
// occupy; used to refuse header counts the file cannot hold before anything is reserved.
std::uint64_t minBytesPerItem(const Element& e, bool binary) {
  std::uint64_t n = 0;
  for (const Property& p : e.props) n += binary ? sizeOf(p.isList ? p.countType : p.type) : 2;
  return n;
}

void checkCounts(const std::string& path, const Header& h, std::size_t available) {
  const bool binary = h.encoding != Encoding::Ascii;
  std::uint64_t need = 0;
  for (const Element& e : h.elements) {
    const std::uint64_t per = minBytesPerItem(e, binary);
    if (per == 0) continue;
    const std::uint64_t limit = binary ? available : available + 1;  // the last ASCII value needs no separator
    if (e.count > limit / per || need + e.count * per > limit)
      throw InputError(path, e.line,
                       "header declares " + std::to_string(e.count) + " '" + e.name + "' elements, but only " +
                           std::to_string(available) + " bytes of data follow the header (truncated file or wrong count)");
    need += e.count * per;
  }
}

// What is being read, for messages; formatted only when something goes wrong.
struct Where {
  const std::string& element;
  std::uint64_t index;
  const char* part;  // "", " list count", " list item"
  std::string text() const { return element + " " + std::to_string(index) + part; }
};

// Reads one value as double from either encoding.
class ValueSource {
 public:
  virtual ~ValueSource() = default;
  virtual double value(Type t, const Where& where) = 0;
  virtual long line() const = 0;
  virtual std::size_t offset() const = 0;  // bytes of the body read so far
};

class BinarySource : public ValueSource {
 public:
  BinarySource(std::string_view data, const std::string& path, bool bigEndian) : in_(data, path, bigEndian) {}
  double value(Type t, const Where& where) override {
    if (in_.remaining() < sizeOf(t)) in_.need(sizeOf(t), where.text());
    const std::string what;  // the size was checked above
    switch (t) {
      case Type::Int8: return in_.read<std::int8_t>(what);
      case Type::UInt8: return in_.read<std::uint8_t>(what);
      case Type::Int16: return in_.read<std::int16_t>(what);
      case Type::UInt16: return in_.read<std::uint16_t>(what);
      case Type::Int32: return in_.read<std::int32_t>(what);
      case Type::UInt32: return in_.read<std::uint32_t>(what);
      case Type::Int64: return static_cast<double>(in_.read<std::int64_t>(what));
      case Type::UInt64: return static_cast<double>(in_.read<std::uint64_t>(what));
      case Type::Float32: return in_.read<float>(what);
      case Type::Float64: return in_.read<double>(what);
    }
    return 0;
  }
  long line() const override { return 0; }
  std::size_t offset() const override { return in_.offset(); }
  std::size_t remaining() const { return in_.remaining(); }

 private:
  ByteReader in_;
};

class AsciiSource : public ValueSource {
 public:
  AsciiSource(std::string_view data, const std::string& path, long firstLine) : s_(data, path) { firstLine_ = firstLine; }
  double value(Type t, const Where& where) override {
    std::string_view tok;
    if (!s_.tokenAcrossLines(tok)) {
      throw InputError(s_.file(), line(), "unexpected end of file while reading " + where.text() + " (file truncated?)");
    }
    if (isInteger(t)) {
      std::int64_t v = 0;
      if (!parseIntToken(tok, v))
        throw InputError(s_.file(), line(),
                         "cannot parse " + where.text() + " from " + quoteToken(tok) + " (expected an integer)");
      return static_cast<double>(v);
    }
    double v = 0;
    if (!parseDoubleToken(tok, v))
      throw InputError(s_.file(), line(), "cannot parse " + where.text() + " from " + quoteToken(tok) + " (not a number)");
    return v;
  }
  long line() const override { return firstLine_ + s_.lineNumber(); }
  std::size_t offset() const override { return s_.offsetAfterLine(); }
  void expectEnd() {
    std::string_view tok;
    if (s_.tokenAcrossLines(tok))
      throw InputError(s_.file(), line(), "unexpected extra data " + quoteToken(tok) + " after the last element");
  }

 private:
  TextScanner s_;
  long firstLine_ = 0;
};

std::uint64_t listCount(const std::string& path, ValueSource& src, const Property& p, const Where& w) {
  const double c = src.value(p.countType, Where{w.element, w.index, " list count"});
  if (c < 0) throw InputError(path, src.line(), w.text() + " has a negative list count");
  if (c > 4294967295.0) throw InputError(path, src.line(), w.text() + " has an absurd list count (" + std::to_string(c) + ")");
  return static_cast<std::uint64_t>(c);
}

void readElements(const std::string& path, const Header& h, const Layout& l, ValueSource& src, BinarySource* bin,
                  MeshBuilder& b) {
  std::vector<std::int64_t> poly;
  for (const Element& e : h.elements) {
    if (e.props.empty()) continue;
    const bool isVertex = &e == l.vertex, isFace = &e == l.face;
    for (std::uint64_t i = 0; i < e.count; ++i) {
      b.step();  // every instance, of any element (empty lists and all): no stretch unchecked
      const Where what{e.name, i, ""};
      const Where item{e.name, i, " list item"};
      double xyz[3] = {0, 0, 0};
      long line = 0;
      for (std::size_t p = 0; p < e.props.size(); ++p) {
        const Property& prop = e.props[p];
        if (!prop.isList) {
          const double v = src.value(prop.type, what);
          if (p == 0) line = src.line();
          if (isVertex)
            for (int a = 0; a < 3; ++a)
              if (l.xyz[a] == static_cast<int>(p)) xyz[a] = v;
          continue;
        }
        const std::uint64_t n = listCount(path, src, prop, what);
        if (p == 0) line = src.line();
        if (bin && n > bin->remaining() / sizeOf(prop.type))
          throw InputError(path, what.text() + " claims a list of " + std::to_string(n) + " items but only " +
                                     std::to_string(bin->remaining()) + " bytes remain (file truncated?)");
        const bool isIndexList = isFace && l.indices == static_cast<int>(p);
        if (isIndexList) {
          poly.clear();
          line = src.line();
        }
        for (std::uint64_t k = 0; k < n; ++k) {
          b.step();
          const double v = src.value(prop.type, item);
          if (!isIndexList) continue;
          if (v != std::floor(v) || !std::isfinite(v))
            throw InputError(path, src.line(), what.text() + ": vertex index is not an integer");
          poly.push_back(v < -1e18 || v > 1e18 ? -1 : static_cast<std::int64_t>(v));
        }
      }
      if (isVertex) b.addVertex({xyz[0], xyz[1], xyz[2]}, line);
      if (isFace) b.addPolygon(poly, l.vertex->count, line, i);
    }
  }
}

void appendHeader(std::string& out, const TriangleMesh& mesh, const char* format,
                  const std::vector<std::string>& comments) {
  out += "ply\nformat ";
  out += format;
  out += " 1.0\n";
  for (const std::string& c : commentLinesToWrite(comments)) out += "comment " + c + "\n";
  out += "element vertex " + std::to_string(mesh.vertices.size()) +
         "\nproperty double x\nproperty double y\nproperty double z\nelement face " +
         std::to_string(mesh.triangles.size()) + "\nproperty list uchar int vertex_indices\nend_header\n";
}

}  // namespace

RawMesh readPly(const std::string& path, std::string_view data, const StageProgress* progress) {
  const Header h = parseHeader(path, data);
  const Layout l = findLayout(path, h);
  const std::string_view body = data.substr(h.dataOffset);
  checkCounts(path, h, body.size());

  RawMesh out;
  MeshBuilder b(path);
  b.reserve(static_cast<std::size_t>(l.vertex->count), static_cast<std::size_t>(l.face->count));  // checked above
  if (h.encoding == Encoding::Ascii) {
    out.format = "ply-ascii";
    AsciiSource src(body, path, h.lastLine);
    b.watch(progress, [&src] { return src.offset(); }, body.size());
    readElements(path, h, l, src, nullptr, b);
    b.watch(nullptr, {}, 1);  // the offset reads `src`, which ends here
    src.expectEnd();
  } else {
    out.format = "ply-binary";
    BinarySource src(body, path, h.encoding == Encoding::BinaryBE);
    b.watch(progress, [&src] { return src.offset(); }, body.size());
    readElements(path, h, l, src, &src, b);
    b.watch(nullptr, {}, 1);  // the offset reads `src`, which ends here
    if (src.remaining() != 0)
      out.notes.push_back("PLY: " + std::to_string(src.remaining()) + " bytes after the last element were ignored");
  }
  out.mesh = b.finish(out.notes);
  out.comments = h.comments;
  return out;
}

std::string writePly(const TriangleMesh& mesh, const std::string& path, bool binary,
                     const std::vector<std::string>& comments) {
  if (mesh.vertices.size() > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
    throw InputError(path, "too many vertices for PLY 'int' indices");
  std::string out;
  if (binary) {
    appendHeader(out, mesh, "binary_little_endian", comments);
    out.reserve(out.size() + mesh.vertices.size() * 24 + mesh.triangles.size() * 13);
    for (const Vec3& p : mesh.vertices)
      for (double v : {p.x, p.y, p.z}) appendLittleEndian(out, v);
    for (const Triangle& t : mesh.triangles) {
      appendLittleEndian(out, std::uint8_t{3});
      for (std::uint32_t i : t) appendLittleEndian(out, static_cast<std::int32_t>(i));
    }
    return out;
  }
  appendHeader(out, mesh, "ascii", comments);
  appendVertexAndTriangleLines(out, mesh);
  return out;
}

}  // namespace reamsim::io
