#pragma once
// Internal to the VTP reader: the parts of a VTK XML PolyData file it reads, found by a small XML scanner
// (tags, attributes with either quote and entities, comments, declarations; no CDATA). The scanner stops at
// <AppendedData>, whose bytes after the '_' marker are raw binary.
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace reamsim::io {

using Attributes = std::map<std::string, std::string>;

// A DataArray and where it sits (the section it belongs to: Points, Polys, Strips, ...).
struct ArrayElement {
  std::string section;
  Attributes attrs;
  std::string_view text;  // inline content (ascii numbers or base64); a view into the file's bytes
};

struct VtpDocument {
  Attributes file;                    // <VTKFile>
  std::vector<Attributes> pieces;     // <Piece>
  std::vector<ArrayElement> arrays;   // the DataArrays of the first piece's Points, Polys and Strips, and
                                      // the PolyData's FieldData arrays (section "FieldData")
  std::optional<Attributes> appended; // <AppendedData>
  std::string_view appendedBytes;     // after its '_' marker
};

// Scans the file; throws InputError naming `path` for malformed XML (unterminated tags or comments,
// mismatched closing tags, nesting deeper than 64, unknown entities, a file that ends inside an element).
VtpDocument scanVtpDocument(const std::string& path, std::string_view data);

}  // namespace reamsim::io
