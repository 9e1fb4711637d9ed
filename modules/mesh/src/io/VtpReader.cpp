// VTK XML PolyData (.vtp) reader of our own. VTK 9.1's vtkXMLPolyDataReader trusts what the file declares:
// a negative NumberOfPoints, a zero compressed block size, an appended offset one byte off or a huge
// NumberOfComponents crash it, hang it or make it allocate gigabytes (fuzzing, session 26). Here every count,
// size and offset is checked against the bytes the file really holds before anything is allocated, and every
// problem is an InputError naming the file.
//
// Read: one Piece; Points (any numeric type, 3 components); Polys and Strips (connectivity + offsets, any
// integer type); Verts and Lines are counted and ignored. Data arrays: format ascii, binary (base64; as VTK
// writes it, one stream for an uncompressed block, two for a compressed one: its header, then its data) or
// appended (raw or base64 encoding);
// header_type UInt32 or UInt64; byte_order either; compressor none or vtkZLibDataCompressor.
#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "Formats.h"
#include "MeshBuilder.h"
#include "TextScanner.h"
#include "VtpDocument.h"
#include "reamsim/mesh/MeshError.h"

namespace reamsim::io {
namespace {

constexpr std::uint64_t kMaxInflateRatio = 1032;  // zlib's largest expansion of one byte of input

// ---- values ----------------------------------------------------------------------------------------------

struct ScalarType {
  int bytes = 0;
  bool isFloat = false, isSigned = false;
};

std::optional<ScalarType> scalarType(const std::string& name) {
  static const std::map<std::string, ScalarType> types = {
      {"Int8", {1, false, true}},   {"UInt8", {1, false, false}},  {"Int16", {2, false, true}},
      {"UInt16", {2, false, false}}, {"Int32", {4, false, true}},  {"UInt32", {4, false, false}},
      {"Int64", {8, false, true}},  {"UInt64", {8, false, false}}, {"Float32", {4, true, true}},
      {"Float64", {8, true, true}}};
  const auto it = types.find(name);
  if (it == types.end()) return std::nullopt;
  return it->second;
}

// Everything a DataArray's values are decoded with.
struct Layout {
  bool bigEndian = false;
  int headerBytes = 4;  // UInt32 or UInt64
  bool zlib = false;
};

std::uint64_t readUnsigned(const unsigned char* p, int bytes, bool bigEndian) {
  std::uint64_t v = 0;
  for (int k = 0; k < bytes; ++k) v |= std::uint64_t(p[bigEndian ? bytes - 1 - k : k]) << (8 * k);
  return v;
}

class ArrayDecoder {
 public:
  ArrayDecoder(const std::string& path, const Layout& layout, std::string_view appended, bool appendedBase64)
      : path_(path), layout_(layout), appended_(appended), appendedBase64_(appendedBase64) {}

  // `progress` (may be null) is asked whether to go on before each array and as its decoding goes (every 64
  // compressed blocks, 4 MiB of base64, 65,536 text values), at the fraction `at()` says (the mesh builder's:
  // the arrays are decoded between its steps). ReadCancelled when it says stop.
  void watch(const StageProgress* progress, std::function<double()> at) {
    progress_ = progress;
    at_ = std::move(at);
  }
  void check() const {
    if (progress_) askReadGoesOn(progress_, at_());
  }

  // The array's values as doubles (points) or int64 (indices). `expected`: the number of values, or -1
  // when the array's own size tells it (connectivity), then bounded by `limit`.
  template <class Out>
  std::vector<Out> values(const ArrayElement& a, const std::string& what, std::int64_t expected, std::uint64_t limit) {
    check();
    const std::string typeName = attr(a, "type");
    const std::optional<ScalarType> type = scalarType(typeName);
    if (!type) fail(what + " has an unknown type \"" + typeName + "\"");
    if (std::is_integral_v<Out> && type->isFloat) fail(what + " must hold integers, not " + typeName);
    const std::string format = attr(a, "format", "ascii");
    if (format == "ascii") return asciiValues<Out>(a.text, *type, what, expected, limit);
    // The block's size as declared is checked against what the array must hold before anything is allocated.
    const std::uint64_t typeBytes = std::uint64_t(type->bytes);
    const std::int64_t exactBytes = expected >= 0 ? std::int64_t(std::uint64_t(expected) * typeBytes) : -1;
    const std::uint64_t maxBytes = limit * typeBytes;
    std::string bytes;
    if (format == "binary") {
      bytes = binaryBlock(a.text, true, what, exactBytes, maxBytes);
    } else if (format == "appended") {
      const std::string off = attr(a, "offset");
      std::uint64_t offset = 0;
      const auto r = std::from_chars(off.data(), off.data() + off.size(), offset);
      if (r.ec != std::errc() || r.ptr != off.data() + off.size())
        fail(what + " has an invalid offset \"" + off + "\"");
      if (offset > appended_.size())
        fail(what + " starts at offset " + off + ", beyond the " + std::to_string(appended_.size()) +
             " bytes of appended data (file truncated?)");
      bytes = binaryBlock(appended_.substr(std::size_t(offset)), appendedBase64_, what, exactBytes, maxBytes);
    } else {
      fail(what + " has an unknown format \"" + format + "\"");
    }
    if (bytes.size() % std::size_t(type->bytes) != 0)
      fail(what + " holds " + std::to_string(bytes.size()) + " bytes, not a whole number of " + typeName + " values");
    const std::uint64_t n = bytes.size() / std::size_t(type->bytes);
    checkCount(n, what, expected, limit);
    std::vector<Out> out(n);
    const auto* p = reinterpret_cast<const unsigned char*>(bytes.data());
    for (std::uint64_t k = 0; k < n; ++k) out[k] = convert<Out>(p + k * type->bytes, *type, what);
    return out;
  }

 private:
  // An attribute's value, or `fallback` when it is absent.
  static std::string attr(const ArrayElement& a, const char* key, const char* fallback = "") {
    const auto it = a.attrs.find(key);
    return it == a.attrs.end() ? fallback : it->second;
  }

  void checkCount(std::uint64_t n, const std::string& what, std::int64_t expected, std::uint64_t limit) const {
    if (expected >= 0 && n != std::uint64_t(expected))
      fail(what + " holds " + std::to_string(n) + " values, the file declares " + std::to_string(expected));
    if (expected < 0 && n > limit) fail(what + " holds " + std::to_string(n) + " values, more than " + std::to_string(limit));
  }

  template <class Out>
  std::vector<Out> asciiValues(std::string_view text, const ScalarType& type, const std::string& what,
                               std::int64_t expected, std::uint64_t limit) const {
    std::vector<Out> out;
    std::size_t k = 0;
    while (true) {
      while (k < text.size() && std::isspace(static_cast<unsigned char>(text[k]))) ++k;
      if (k >= text.size()) break;
      std::size_t e = k;
      while (e < text.size() && !std::isspace(static_cast<unsigned char>(text[e]))) ++e;
      const std::string_view token = text.substr(k, e - k);
      if ((expected >= 0 && out.size() >= std::size_t(expected)) || out.size() >= limit)
        fail(what + " holds more values than " +
             (expected >= 0 ? "the file declares (" + std::to_string(expected) + ")" : std::to_string(limit)));
      out.push_back(parseToken<Out>(token, type, what, out.size()));
      if ((out.size() & 65535) == 0) check();
      k = e;
    }
    checkCount(out.size(), what, expected, limit);
    return out;
  }

  // One ascii value, parsed as the other text formats parse theirs (TextScanner.h).
  template <class Out>
  Out parseToken(std::string_view token, const ScalarType& type, const std::string& what, std::size_t index) const {
    if constexpr (std::is_integral_v<Out>) {
      std::int64_t v = 0;
      if (!parseIntToken(token, v)) fail(what + " value " + std::to_string(index) + " is not an integer: " + quoteToken(token));
      return v;
    } else {
      double v = 0;
      if (!parseDoubleToken(token, v)) fail(what + " value " + std::to_string(index) + " is not a number: " + quoteToken(token));
      // A Float32 array holds floats: its text is read to the nearest float, as VTK reads it, so that the
      // bundled scapula (ascii Float32) keeps the coordinates it always had.
      if (type.isFloat && type.bytes == 4) {
        if (token.size() > 1 && token[0] == '+') token.remove_prefix(1);
        float f = 0;
        const auto rf = std::from_chars(token.data(), token.data() + token.size(), f);
        if (rf.ec == std::errc() && rf.ptr == token.data() + token.size()) return static_cast<double>(f);
        if (std::abs(v) < 1) return std::copysign(0.0, v);  // below the smallest float
        return std::copysign(std::numeric_limits<double>::infinity(), v);  // beyond the largest: refused as non-finite
      }
      return v;
    }
  }

  template <class Out>
  Out convert(const unsigned char* p, const ScalarType& type, const std::string& what) const {
    const std::uint64_t raw = readUnsigned(p, type.bytes, layout_.bigEndian);
    if (type.isFloat) {
      if (type.bytes == 4) {
        const std::uint32_t u = std::uint32_t(raw);
        float f;
        std::memcpy(&f, &u, 4);
        return static_cast<Out>(f);
      }
      double d;
      std::memcpy(&d, &raw, 8);
      return static_cast<Out>(d);
    }
    if (type.isSigned) {
      const int shift = 64 - 8 * type.bytes;
      const std::int64_t v = std::int64_t(raw << shift) >> shift;
      return static_cast<Out>(v);
    }
    if constexpr (std::is_integral_v<Out>) {
      if (raw > std::uint64_t(INT64_MAX)) fail(what + " holds an index above 2^63");
    }
    return static_cast<Out>(raw);
  }

  // The bytes of one binary block (header + data) starting at `in`, base64 or raw.
  std::string binaryBlock(std::string_view in, bool base64, const std::string& what, std::int64_t exactBytes,
                          std::uint64_t maxBytes) const {
    auto checkSize = [&](std::uint64_t n) {
      if (exactBytes >= 0 && n != std::uint64_t(exactBytes))
        fail(what + " holds " + std::to_string(n) + " bytes, the file declares " + std::to_string(exactBytes));
      if (n > maxBytes) fail(what + " declares " + std::to_string(n) + " bytes, more than the file can hold");
    };
    Source src(*this, in, base64, what);
    const int w = layout_.headerBytes;
    if (!layout_.zlib) {
      // Uncompressed, VTK encodes the size header and the data as one base64 stream.
      const std::string header = src.peekHeader(std::size_t(w), "its size header");
      const std::uint64_t nbytes = readUnsigned(reinterpret_cast<const unsigned char*>(header.data()), w, layout_.bigEndian);
      if (nbytes > src.remainingBytesBound())
        fail(what + " declares " + std::to_string(nbytes) + " bytes, more than the file holds (corrupt or truncated)");
      checkSize(nbytes);
      return src.take(std::size_t(w + nbytes), "its data").substr(std::size_t(w));
    }
    // zlib: [nblocks][blockSize][lastBlockSize][compressed size of each block], then the blocks.
    const std::string h3 = src.peekHeader(std::size_t(3 * w), "its compression header");
    const auto* hp = reinterpret_cast<const unsigned char*>(h3.data());
    const std::uint64_t nblocks = readUnsigned(hp, w, layout_.bigEndian);
    const std::uint64_t blockSize = readUnsigned(hp + w, w, layout_.bigEndian);
    const std::uint64_t lastSize = readUnsigned(hp + 2 * w, w, layout_.bigEndian);
    if (nblocks == 0) {
      checkSize(0);
      return {};
    }
    if (nblocks > src.remainingBytesBound() / std::uint64_t(w))
      fail(what + " declares " + std::to_string(nblocks) + " compressed blocks, more than the file can hold");
    if (blockSize == 0 || lastSize > blockSize)
      fail(what + " has an invalid compression header (block size " + std::to_string(blockSize) + ", last block " +
           std::to_string(lastSize) + ")");
    const std::string header = src.take(std::size_t((3 + nblocks) * std::uint64_t(w)), "its compression header");
    std::vector<std::uint64_t> csize(nblocks);
    std::uint64_t ctotal = 0;
    for (std::uint64_t b = 0; b < nblocks; ++b) {
      csize[b] = readUnsigned(reinterpret_cast<const unsigned char*>(header.data()) + (3 + b) * w, w, layout_.bigEndian);
      ctotal += csize[b];
      if (csize[b] == 0 || ctotal > src.remainingBytesBound())
        fail(what + " declares compressed blocks larger than the file holds (corrupt or truncated)");
    }
    const std::uint64_t last = lastSize == 0 ? blockSize : lastSize;
    const std::uint64_t expandable = kMaxInflateRatio * ctotal;
    if (nblocks - 1 > expandable / blockSize || (nblocks - 1) * blockSize + last > expandable)
      fail(what + " declares " + std::to_string(nblocks) + " blocks of " + std::to_string(blockSize) +
           " bytes, more than its " + std::to_string(ctotal) + " compressed bytes can expand to");
    const std::uint64_t total = (nblocks - 1) * blockSize + last;
    checkSize(total);
    const std::string compressed = src.take(std::size_t(ctotal), "its compressed data");
    std::string out(std::size_t(total), '\0');
    std::uint64_t read = 0, at = 0;
    for (std::uint64_t b = 0; b < nblocks; ++b) {
      if ((b & 63) == 63) check();
      const std::uint64_t want = b + 1 == nblocks ? last : blockSize;
      uLongf got = uLongf(want);
      const int rc = uncompress(reinterpret_cast<Bytef*>(out.data() + at), &got,
                                reinterpret_cast<const Bytef*>(compressed.data() + read), uLong(csize[b]));
      if (rc != Z_OK || got != want)
        fail(what + ": compressed block " + std::to_string(b) + " is corrupt (zlib: " +
             (rc == Z_OK ? "wrong size" : rc == Z_BUF_ERROR ? "expands beyond its declared size" : "invalid data") + ")");
      read += csize[b];
      at += want;
    }
    return out;
  }

  // Reads bytes from a raw or base64 region.
  class Source {
   public:
    Source(const ArrayDecoder& d, std::string_view in, bool base64, const std::string& what)
        : d_(d), in_(in), base64_(base64), what_(what) {}
    // Bytes left, or for base64 an upper bound of them (3 per 4 characters).
    std::uint64_t remainingBytesBound() const {
      const std::size_t left = in_.size() - pos_;
      return base64_ ? left / 4 * 3 + 3 : left;
    }
    std::string peekHeader(std::size_t n, const char* part) {
      const std::size_t save = pos_;
      std::string h = take(n, part);
      pos_ = save;
      return h;
    }
    // n bytes; where the input is base64, the first n of a stream starting here (a compressed block's header
    // is a padded stream of its own, its data another).
    std::string take(std::size_t n, const char* part) {
      if (!base64_) {
        if (n > in_.size() - pos_) d_.fail(d_.truncated(what_, part));
        std::string out(in_.substr(pos_, n));
        pos_ += n;
        return out;
      }
      const std::size_t chars = (n + 2) / 3 * 4;  // the stream's characters, whitespace left out
      std::string text;
      text.reserve(chars);
      while (text.size() < chars && pos_ < in_.size()) {
        if ((pos_ & ((std::size_t{1} << 22) - 1)) == 0) d_.check();
        const char c = in_[pos_++];
        if (!std::isspace(static_cast<unsigned char>(c))) text += c;
      }
      if (text.size() < chars) d_.fail(d_.truncated(what_, part));
      std::string out = decodeBase64(text);
      if (out.size() < n) d_.fail(what_ + ": " + part + " is not valid base64");
      out.resize(n);
      return out;
    }

   private:
    std::string decodeBase64(const std::string& text) const {
      std::string out;
      out.reserve(text.size() / 4 * 3);
      for (std::size_t k = 0; k < text.size(); k += 4) {
        if ((k & ((std::size_t{1} << 22) - 1)) == 0) d_.check();
        int v[4];
        int pad = 0;
        for (int j = 0; j < 4; ++j) {
          const char c = text[k + j];
          if (c == '=') {
            v[j] = 0;
            ++pad;
          } else if (pad > 0 || (v[j] = sextet(c)) < 0) {
            d_.fail(what_ + " has invalid base64 data");
          }
        }
        if (pad > 2) d_.fail(what_ + " has invalid base64 padding");
        const std::uint32_t bits = (std::uint32_t(v[0]) << 18) | (std::uint32_t(v[1]) << 12) | (std::uint32_t(v[2]) << 6) | std::uint32_t(v[3]);
        out += char(bits >> 16);
        if (pad < 2) out += char((bits >> 8) & 0xff);
        if (pad < 1) out += char(bits & 0xff);
      }
      return out;
    }
    static int sextet(char c) {
      if (c >= 'A' && c <= 'Z') return c - 'A';
      if (c >= 'a' && c <= 'z') return c - 'a' + 26;
      if (c >= '0' && c <= '9') return c - '0' + 52;
      if (c == '+') return 62;
      if (c == '/') return 63;
      return -1;
    }
    const ArrayDecoder& d_;
    std::string_view in_;
    bool base64_;
    const std::string& what_;
    std::size_t pos_ = 0;
  };

  std::string truncated(const std::string& w, const char* part) const {
    return w + ": " + part + " runs past the end of the data (file truncated?)";
  }
  [[noreturn]] void fail(const std::string& problem) const { throw InputError(path_, problem); }

  const std::string& path_;
  Layout layout_;
  std::string_view appended_;
  bool appendedBase64_;
  const StageProgress* progress_ = nullptr;
  std::function<double()> at_;
};

// A count attribute of <Piece>: a non-negative integer (absent: 0).
std::uint64_t pieceCount(const std::string& path, const Attributes& piece, const char* key) {
  const auto it = piece.find(key);
  if (it == piece.end()) return 0;
  const std::string& v = it->second;
  std::uint64_t n = 0;
  const auto r = std::from_chars(v.data(), v.data() + v.size(), n);
  if (r.ec != std::errc() || r.ptr != v.data() + v.size())
    throw InputError(path, std::string(key) + " = \"" + v + "\" is not a non-negative integer");
  return n;
}

const ArrayElement* findArray(const VtpDocument& doc, const std::string& section, const char* name) {
  for (const ArrayElement& a : doc.arrays) {
    if (a.section != section) continue;
    const auto it = a.attrs.find("Name");
    if (!name || (it != a.attrs.end() && it->second == name)) return &a;
  }
  return nullptr;
}

// The cells of one section (Polys or Strips) as lists of point ids.
void readCells(const std::string& path, const VtpDocument& doc, ArrayDecoder& dec, const std::string& section,
               std::uint64_t cells, std::uint64_t sizeLimit, const std::function<void(const std::int64_t*, std::size_t)>& cell) {
  if (cells == 0) return;
  const ArrayElement* conn = findArray(doc, section, "connectivity");
  const ArrayElement* offs = findArray(doc, section, "offsets");
  if (!conn || !offs)
    throw InputError(path, section + " declares " + std::to_string(cells) + " cells but has no " +
                               (!conn ? "connectivity" : "offsets") + " array");
  const std::vector<std::int64_t> offsets = dec.values<std::int64_t>(*offs, section + " offsets", -1, cells + 1);
  const std::vector<std::int64_t> ids = dec.values<std::int64_t>(*conn, section + " connectivity", -1, sizeLimit);
  // VTK's XML format stores each cell's end; its in-memory layout (and some writers) a leading 0 as well.
  std::size_t first = 0;
  if (offsets.size() == cells + 1 && offsets[0] == 0) first = 1;
  else if (offsets.size() != cells)
    throw InputError(path, section + " offsets hold " + std::to_string(offsets.size()) + " values for " +
                               std::to_string(cells) + " cells");
  std::int64_t begin = 0;
  for (std::size_t c = first; c < offsets.size(); ++c) {
    const std::int64_t end = offsets[c];
    if (end < begin || std::uint64_t(end) > ids.size())
      throw InputError(path, section + " offsets are invalid at cell " + std::to_string(c - first) + " (offset " +
                                 std::to_string(end) + ", connectivity holds " + std::to_string(ids.size()) + ")");
    cell(ids.data() + begin, std::size_t(end - begin));
    begin = end;
  }
}

// ReamSim's comments (kVtpCommentsArray in the field data): a string array, each value ended by a NUL byte,
// stored as VTK stores strings in every format (ascii: the bytes as numbers).
std::vector<std::string> readComments(const VtpDocument& doc, ArrayDecoder& dec, std::uint64_t limit) {
  const ArrayElement* a = findArray(doc, "FieldData", kVtpCommentsArray);
  if (!a) return {};
  ArrayElement bytes = *a;
  if (const auto t = bytes.attrs.find("type"); t == bytes.attrs.end() || t->second != "String") return {};
  bytes.attrs["type"] = "UInt8";
  std::vector<std::string> out(1);
  for (const std::int64_t c : dec.values<std::int64_t>(bytes, std::string("the ") + kVtpCommentsArray + " array", -1, limit)) {
    if (c == 0) out.emplace_back();
    else out.back() += char(c);
  }
  out.pop_back();  // after the last NUL
  return out;
}

// The first bytes, before any scanning: binary garbage gets a message about what the file is not.
void checkLooksLikeVtkXml(const std::string& path, std::string_view data) {
  std::size_t i = 0;
  if (data.substr(0, 3) == "\xEF\xBB\xBF") i = 3;  // UTF-8 BOM
  while (i < data.size() && std::isspace(static_cast<unsigned char>(data[i]))) ++i;
  const std::string_view head = data.substr(i, 512);
  if (head.substr(0, 1) != "<" || (head.find("<?xml") != 0 && head.find("<VTKFile") == std::string_view::npos))
    throw InputError(path, "not a VTK XML file (expected '<?xml' or '<VTKFile' at the start)");
}

}  // namespace

RawMesh readVtp(const std::string& path, std::string_view data, const StageProgress* progress) {
  checkLooksLikeVtkXml(path, data);
  const VtpDocument doc = scanVtpDocument(path, data);
  if (doc.file.empty()) throw InputError(path, "not a VTK XML file (no <VTKFile> element)");
  const auto type = doc.file.find("type");
  if (type == doc.file.end() || type->second != "PolyData")
    throw InputError(path, "not a VTK PolyData file (the VTKFile type is not \"PolyData\")");
  if (doc.pieces.empty()) throw InputError(path, "the file has no <Piece> (no points or polygons)");
  if (doc.pieces.size() > 1)
    throw InputError(path, "the file has " + std::to_string(doc.pieces.size()) + " pieces; only single-piece files are read");

  Layout layout;
  if (const auto it = doc.file.find("byte_order"); it != doc.file.end()) {
    if (it->second != "LittleEndian" && it->second != "BigEndian")
      throw InputError(path, "unknown byte_order \"" + it->second + "\"");
    layout.bigEndian = it->second == "BigEndian";
  }
  if (const auto it = doc.file.find("header_type"); it != doc.file.end()) {
    if (it->second != "UInt32" && it->second != "UInt64")
      throw InputError(path, "unknown header_type \"" + it->second + "\" (UInt32 or UInt64)");
    layout.headerBytes = it->second == "UInt64" ? 8 : 4;
  }
  if (const auto it = doc.file.find("compressor"); it != doc.file.end() && !it->second.empty()) {
    if (it->second != "vtkZLibDataCompressor")
      throw InputError(path, "compressor \"" + it->second + "\" is not supported (only vtkZLibDataCompressor)");
    layout.zlib = true;
  }
  bool appendedBase64 = false;
  if (doc.appended) {
    const auto it = doc.appended->find("encoding");
    const std::string enc = it == doc.appended->end() ? "base64" : it->second;
    if (enc != "raw" && enc != "base64") throw InputError(path, "<AppendedData> has an unknown encoding \"" + enc + "\"");
    appendedBase64 = enc == "base64";
  }
  ArrayDecoder dec(path, layout, doc.appendedBytes, appendedBase64);

  // Every value takes at least one byte of the file, or 1/1032 of a compressed one.
  const std::uint64_t limit = std::uint64_t(data.size()) * (layout.zlib ? kMaxInflateRatio : 1);
  const Attributes& piece = doc.pieces.front();
  const std::uint64_t np = pieceCount(path, piece, "NumberOfPoints");
  const std::uint64_t npolys = pieceCount(path, piece, "NumberOfPolys");
  const std::uint64_t nstrips = pieceCount(path, piece, "NumberOfStrips");
  const std::uint64_t ignored = pieceCount(path, piece, "NumberOfVerts") + pieceCount(path, piece, "NumberOfLines");
  // Each declared element needs at least `values` values of the file.
  auto checkDeclared = [&](const char* key, std::uint64_t n, std::uint64_t values) {
    if (n > limit / values)
      throw InputError(path, "the file declares " + std::string(key) + " = " + std::to_string(n) + ", more than its size of " +
                                 std::to_string(data.size()) + " bytes can hold (corrupt or lying header)");
  };
  checkDeclared("NumberOfPoints", np, 3);
  checkDeclared("NumberOfPolys", npolys, 1);
  checkDeclared("NumberOfStrips", nstrips, 1);

  RawMesh out;
  out.format = "vtp";
  MeshBuilder b(path);
  // The arrays are decoded whole before the mesh is built: progress by the points added and the cells (polygons
  // and strips) handled.
  std::size_t cellsDone = 0;
  b.watch(progress, [&b, &cellsDone] { return b.vertexCount() + cellsDone; }, std::size_t(np + npolys + nstrips) + 1);
  dec.watch(progress, [&b] { return b.fraction(); });
  if (np > 0) {
    const ArrayElement* points = findArray(doc, "Points", nullptr);
    if (!points) throw InputError(path, "the file declares " + std::to_string(np) + " points but has no Points array");
    const auto comps = points->attrs.find("NumberOfComponents");
    if (comps == points->attrs.end() || comps->second != "3")
      throw InputError(path, "the Points array must have NumberOfComponents=\"3\"");
    const std::vector<double> xyz = dec.values<double>(*points, "the Points array", std::int64_t(np * 3), limit);
    b.reserve(std::size_t(np), std::size_t(npolys));
    for (std::uint64_t i = 0; i < np; ++i) b.addVertex({xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]}, 0);
  }
  std::vector<std::int64_t> ids;
  std::size_t face = 0;
  readCells(path, doc, dec, "Polys", npolys, limit, [&](const std::int64_t* p, std::size_t n) {
    ids.assign(p, p + n);
    ++cellsDone;
    b.addPolygon(ids, np, 0, face++);
  });
  std::size_t stripCount = 0, stripTriangles = 0;
  readCells(path, doc, dec, "Strips", nstrips, limit, [&](const std::int64_t* p, std::size_t n) {
    if (n < 3)
      throw InputError(path, "triangle strip " + std::to_string(stripCount) + " has only " + std::to_string(n) +
                                 " points (at least 3 needed)");
    ++cellsDone;
    for (std::size_t k = 0; k + 2 < n; ++k) {
      const std::int64_t a = p[k], bb = p[k + 1], c = p[k + 2];
      if (a == bb || bb == c || a == c) continue;  // degenerate joint triangle of a strip
      // Alternate the winding so that every triangle keeps the strip's orientation.
      if (k % 2 == 0) ids = {a, bb, c};
      else ids = {bb, a, c};
      b.addPolygon(ids, np, 0, face++);
      ++stripTriangles;
    }
    ++stripCount;
  });
  if (stripCount > 0)
    out.notes.push_back(std::to_string(stripCount) + " triangle strips were converted to " +
                        std::to_string(stripTriangles) + " triangles");
  if (ignored > 0) out.notes.push_back(std::to_string(ignored) + " vertex/line cells were ignored");
  out.comments = readComments(doc, dec, limit);
  out.mesh = b.finish(out.notes);
  return out;
}

}  // namespace reamsim::io
