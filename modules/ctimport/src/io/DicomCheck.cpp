#include "DicomCheck.h"

#include "Bytes.h"

#include <cctype>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace reamsim::ct::io {
namespace {

constexpr std::uint32_t kUndefined = 0xFFFFFFFF;
constexpr int kMaxDepth = 32;  // nested sequences; deeper is a corrupt (or hostile) file

struct Problem {
  std::string what;
};

std::string tagText(std::uint16_t g, std::uint16_t e) {
  char b[16];
  std::snprintf(b, sizeof b, "(%04X,%04X)", unsigned(g), unsigned(e));
  return b;
}

// 'OB', or the bytes in hex when they are not letters.
std::string vrText(const char* v) {
  char b[16];
  if (std::isupper(static_cast<unsigned char>(v[0])) && std::isupper(static_cast<unsigned char>(v[1])))
    std::snprintf(b, sizeof b, "'%c%c'", v[0], v[1]);
  else
    std::snprintf(b, sizeof b, "0x%02X 0x%02X", unsigned(std::uint8_t(v[0])), unsigned(std::uint8_t(v[1])));
  return b;
}

bool knownVr(const char* v) {
  static const char* const all[] = {"AE", "AS", "AT", "CS", "DA", "DS", "DT", "FL", "FD", "IS", "LO", "LT",
                                    "OB", "OD", "OF", "OL", "OV", "OW", "PN", "SH", "SL", "SQ", "SS", "ST",
                                    "SV", "TM", "UC", "UI", "UL", "UN", "UR", "US", "UT", "UV"};
  for (const char* a : all)
    if (v[0] == a[0] && v[1] == a[1]) return true;
  return false;
}

// VRs with two reserved bytes and a 32-bit length in explicit syntaxes.
bool longVr(const char* v) {
  static const char* const all[] = {"OB", "OD", "OF", "OL", "OV", "OW", "SQ", "SV", "UC", "UN", "UR", "UT", "UV"};
  for (const char* a : all)
    if (v[0] == a[0] && v[1] == a[1]) return true;
  return false;
}

class Walker {
 public:
  explicit Walker(std::string_view b) : b_(b) {}

  struct Element {
    std::uint16_t group = 0, element = 0;
    char vr[3] = {0, 0, 0};  // empty in implicit syntaxes
    std::uint32_t length = 0;
    std::size_t value = 0;  // where the value starts
  };

  // The header of the element at `pos`; its defined length is checked against `end`.
  Element element(std::size_t pos, std::size_t end, bool explicitVr, bool bigEndian) const {
    need(pos, 8, end, "element header");
    Element x;
    x.group = u16(pos, bigEndian);
    x.element = u16(pos + 2, bigEndian);
    if (x.group == 0xFFFE) return x;  // item tags: the caller decides
    // vtk-dicom reads an element whose VR bytes are not two capital letters as implicit (some writers mix
    // them); then the 4-byte length must fit like any other (a corrupt VR read so asked for 770 MB).
    const bool vrLetters = std::isupper(static_cast<unsigned char>(b_[pos + 4])) && std::isupper(static_cast<unsigned char>(b_[pos + 5]));
    if (explicitVr && vrLetters) {
      std::memcpy(x.vr, b_.data() + pos + 4, 2);
      if (!knownVr(x.vr))
        throw Problem{"element " + tagText(x.group, x.element) + " has an invalid value representation " + vrText(x.vr)};
      if (longVr(x.vr)) {
        need(pos, 12, end, "element header");
        x.length = u32(pos + 8, bigEndian);
        x.value = pos + 12;
      } else {
        x.length = u16(pos + 6, bigEndian);
        x.value = pos + 8;
      }
    } else {
      x.length = u32(pos + 4, bigEndian);
      x.value = pos + 8;
    }
    if (x.length != kUndefined && x.length > end - x.value)
      throw Problem{"element " + tagText(x.group, x.element) + " claims " + std::to_string(x.length) + " bytes but only " +
                    std::to_string(end - x.value) + " remain (file truncated or corrupt)"};
    return x;
  }

  // The meta group (0002,xxxx) from `pos`, always explicit VR little endian: returns where it ends and the
  // data set's transfer syntax.
  std::size_t metaGroup(std::size_t pos, std::string& syntax) const {
    // Explicit VR little endian by the standard; some writers made it implicit, which vtk-dicom reads too.
    while (pos + 8 <= b_.size() && u16(pos, false) == 0x0002) {
      const Element x = element(pos, b_.size(), true, false);
      if (x.length == kUndefined) throw Problem{"meta element " + tagText(x.group, x.element) + " has an undefined length"};
      if (x.element == 0x0010) syntax.assign(b_.data() + x.value, x.length);
      pos = x.value + x.length;
    }
    while (!syntax.empty() && (syntax.back() == '\0' || syntax.back() == ' ')) syntax.pop_back();
    return pos;
  }

  // Elements from `pos` up to `end`, or up to the item delimiter when `inItem` (undefined-length item).
  std::size_t dataSet(std::size_t pos, std::size_t end, bool explicitVr, bool bigEndian, int depth, bool inItem) {
    if (depth > kMaxDepth) throw Problem{"sequences nested deeper than " + std::to_string(kMaxDepth)};
    std::uint32_t previous = 0;
    bool first = true;
    while (pos < end) {
      // Zero bytes after the last element: vtk-dicom crashes on them in every syntax (session 27,
      // BadVolumes.DicomStructureCheckAcceptsValidLayoutsAndLetsNoCrashThrough), so they are named here.
      if (depth == 0 && !inItem && zerosFrom(pos)) {
        throw Problem{std::to_string(end - pos) + " zero bytes after the last element at byte " + std::to_string(pos) +
                      " (padding that is not a DICOM element; vtk-dicom cannot read it)"};
      }
      const Element x = element(pos, end, explicitVr, bigEndian);
      const std::uint16_t g = x.group, e = x.element;
      if (g == 0xFFFE) {
        if (inItem && e == 0xE00D) return pos + 8;
        throw Problem{"unexpected item tag " + tagText(g, e) + " at byte " + std::to_string(pos)};
      }
      if (g == 0x0000) throw Problem{"command-group element " + tagText(g, e) + " in the data set (corrupt file?)"};
      if (g == 0x0001) throw Problem{"element " + tagText(g, e) + " in the reserved group 0001 (corrupt file?)"};
      // The standard orders elements by tag; vtk-dicom relies on it when it merges the slices' elements.
      const std::uint32_t tag = (std::uint32_t(g) << 16) | e;
      if (!first && tag <= previous)
        throw Problem{"element " + tagText(g, e) + " follows " + tagText(std::uint16_t(previous >> 16), std::uint16_t(previous)) +
                      ": elements out of order (corrupt file?)"};
      previous = tag;
      first = false;
      // A group length (gggg,0000) is one UL; vtk-dicom crashed on one of length 0 in a later slice.
      if (e == 0x0000 && x.length != 4)
        throw Problem{"group length " + tagText(g, e) + " has " + std::to_string(x.length) + " bytes, not 4 (corrupt file?)"};
      const bool un = std::strcmp(x.vr, "UN") == 0;
      // Encapsulated data: the pixel data, or another OB of undefined length (vtk-dicom reads its fragments).
      const bool pixels = (g == 0x7FE0 && e == 0x0010) || (x.length == kUndefined && std::strcmp(x.vr, "OB") == 0);
      const bool sequence = std::strcmp(x.vr, "SQ") == 0 || (x.vr[0] == 0 && x.length == kUndefined && !pixels);
      if (x.length == kUndefined) {
        if (!sequence && !un && !pixels)
          throw Problem{"element " + tagText(g, e) + " has an undefined length, which its VR does not allow"};
        // UN of undefined length holds an implicit little endian sequence; encapsulated pixel data raw fragments.
        pos = items(x.value, end, explicitVr && !un, bigEndian && !un, depth, pixels, true);
        continue;
      }
      if (sequence) items(x.value, x.value + x.length, explicitVr, bigEndian, depth, false, false);
      if (depth == 0) noteShape(tag, x, bigEndian);
      pos = x.value + x.length;
    }
    if (inItem) throw Problem{"an item without its end (file truncated?)"};
    return pos;
  }

  // Rows, Columns and NumberOfFrames of the top-level data set, as far as they were found.
  std::uint64_t rows = 1, columns = 1, frames = 1;

 private:
  void noteShape(std::uint32_t tag, const Element& x, bool bigEndian) {
    if ((tag == 0x00280010 || tag == 0x00280011) && x.length == 2) (tag == 0x00280010 ? rows : columns) = u16(x.value, bigEndian);
    if (tag == 0x00280008 && x.length > 0 && x.length < 16) {  // IS: decimal text
      const std::string text(b_.substr(x.value, x.length));
      const long long n = std::strtoll(text.c_str(), nullptr, 10);
      if (n > 0) frames = std::uint64_t(n);
    }
  }

  // Items of a sequence (or pixel data fragments) from `pos`; up to the sequence delimiter when `undefined`.
  std::size_t items(std::size_t pos, std::size_t end, bool explicitVr, bool bigEndian, int depth, bool fragments,
                    bool undefined) {
    while (pos < end) {
      need(pos, 8, end, "item header");
      const std::uint16_t g = u16(pos, bigEndian), e = u16(pos + 2, bigEndian);
      const std::uint32_t length = u32(pos + 4, bigEndian);
      if (g == 0xFFFE && e == 0xE0DD && undefined) return pos + 8;
      if (g != 0xFFFE || e != 0xE000) throw Problem{"expected an item, found " + tagText(g, e) + " at byte " + std::to_string(pos)};
      pos += 8;
      if (length == kUndefined) {
        if (fragments) throw Problem{"pixel data fragment of undefined length"};
        pos = dataSet(pos, end, explicitVr, bigEndian, depth + 1, true);
        continue;
      }
      if (length > end - pos)
        throw Problem{"item claims " + std::to_string(length) + " bytes but only " + std::to_string(end - pos) +
                      " remain (file truncated or corrupt)"};
      if (!fragments) dataSet(pos, pos + length, explicitVr, bigEndian, depth + 1, false);
      pos += length;
    }
    if (undefined) throw Problem{"a sequence without its end (file truncated?)"};
    return pos;
  }

  bool zerosFrom(std::size_t pos) const { return b_.find_first_not_of('\0', pos) == std::string_view::npos; }
  void need(std::size_t pos, std::size_t n, std::size_t end, const char* what) const {
    if (n > end - pos) throw Problem{std::string("the file ends inside an ") + what + " (file truncated?)"};
  }
  std::uint16_t u16(std::size_t p, bool be) const { return loadScalar<std::uint16_t>(b_.data() + p, be); }
  std::uint32_t u32(std::size_t p, bool be) const { return loadScalar<std::uint32_t>(b_.data() + p, be); }

  std::string_view b_;
};

}  // namespace

std::string dicomStructureProblem(std::string_view b) {
  try {
    Walker w(b);
    std::size_t pos = 0;
    if (b.size() >= 132 && b.substr(128, 4) == "DICM") pos = 132;
    else if (b.substr(0, 4) == "DICM") pos = 4;
    std::string syntax;
    const std::size_t metaStart = pos;
    pos = w.metaGroup(pos, syntax);
    if (pos > metaStart) w.dataSet(metaStart, pos, true, false, 0, false);  // order and group length, as below
    if (syntax == "1.2.840.10008.1.2.1.99") return "";  // deflated: vtk-dicom inflates it, nothing to walk here
    // Without a meta group, or when the first element contradicts it (a mislabelled file that vtk-dicom still
    // reads), the syntax is guessed from the first element, as vtk-dicom does.
    const bool looksExplicit = pos + 6 <= b.size() && knownVr(b.data() + pos + 4);
    const bool explicitVr = looksExplicit && syntax != "1.2.840.10008.1.2";
    w.dataSet(pos, b.size(), explicitVr, syntax == "1.2.840.10008.1.2.2", 0, false);
    // vtk-dicom sorts frames before it reads any pixel: NumberOfFrames 99999999 in a 4 kB file made it loop for
    // minutes. A frame takes at least one byte in any syntax.
    if (w.frames > b.size())
      return "NumberOfFrames " + std::to_string(w.frames) + " is more than a file of " + std::to_string(b.size()) + " bytes can hold";
    if (w.rows * w.columns * w.frames > (std::uint64_t{1} << 31))
      return "declares " + std::to_string(w.rows) + "×" + std::to_string(w.columns) + "×" + std::to_string(w.frames) +
             " voxels, more than the limit of 2^31 (wrong Rows, Columns or NumberOfFrames?)";
    return "";
  } catch (const Problem& p) {
    return p.what;
  }
}

}  // namespace reamsim::ct::io
