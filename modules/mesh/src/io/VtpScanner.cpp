// The XML scanner of the VTP reader (see VtpDocument.h).
#include <cctype>
#include <charconv>

#include "VtpDocument.h"
#include "reamsim/mesh/MeshError.h"

namespace reamsim::io {
namespace {

constexpr int kMaxDepth = 64;

struct Element {
  std::string name;
  Attributes attrs;
};

class Scanner {
 public:
  Scanner(const std::string& path, std::string_view data) : path_(path), s_(data) {}

  VtpDocument parse() {
    VtpDocument doc;
    std::vector<Element> stack;
    std::size_t textStart = 0;
    while (true) {
      const std::size_t lt = s_.find('<', i_);
      if (lt == std::string_view::npos) break;
      const std::string_view text = s_.substr(textStart, lt - textStart);
      // A DataArray's values are the text right after its start tag (VTK may add InformationKey children after it).
      if (openArray_) doc.arrays.back().text = text;
      openArray_ = false;
      i_ = lt;
      if (startsWith("<!--")) {
        skipPast("-->", "comment");
      } else if (startsWith("<?")) {
        skipPast("?>", "processing instruction");
      } else if (startsWith("<![CDATA[")) {
        fail("CDATA sections are not supported");
      } else if (startsWith("<!")) {
        skipPast(">", "declaration");
      } else if (startsWith("</")) {
        i_ += 2;
        const std::string name = readName();
        skipSpace();
        expect('>');
        if (stack.empty() || stack.back().name != name)
          fail("closing tag </" + name + "> does not match " + (stack.empty() ? "nothing" : "<" + stack.back().name + ">"));
        stack.pop_back();
      } else {
        ++i_;
        Element e;
        e.name = readName();
        bool selfClosing = false;
        readAttributes(e.attrs, selfClosing);
        if (e.name == "AppendedData") {
          doc.appended = e.attrs;
          const std::size_t mark = s_.find('_', i_);
          if (mark == std::string_view::npos) fail("<AppendedData> has no '_' before its data");
          std::string_view rest = s_.substr(mark + 1);
          const std::size_t end = rest.rfind("</AppendedData>");
          if (end != std::string_view::npos) rest = rest.substr(0, end);
          doc.appendedBytes = rest;
          return doc;
        }
        onStart(doc, stack, e);
        if (!selfClosing) {
          if (stack.size() >= std::size_t(kMaxDepth)) fail("elements nested more than " + std::to_string(kMaxDepth) + " deep");
          stack.push_back(std::move(e));
        } else {
          openArray_ = false;
        }
      }
      textStart = i_;
    }
    if (!stack.empty()) fail("the file ends inside <" + stack.back().name + "> (file truncated?)");
    return doc;
  }

 private:
  void onStart(VtpDocument& doc, const std::vector<Element>& stack, const Element& e) {
    const std::string parent = stack.empty() ? "" : stack.back().name;
    if (e.name == "VTKFile") doc.file = e.attrs;
    if (e.name == "Piece" && parent == "PolyData") doc.pieces.push_back(e.attrs);
    if ((e.name == "Array" || e.name == "DataArray") && parent == "FieldData" && doc.pieces.empty()) {
      doc.arrays.push_back({parent, e.attrs, {}});  // the data set's own field data (ReamSim's comments)
      openArray_ = true;
    }
    if (e.name == "DataArray") {
      if (doc.pieces.size() != 1 || stack.size() < 2) return;
      // Only the arrays the mesh needs are kept (point and cell data are skipped).
      if (parent == "Points" || parent == "Polys" || parent == "Strips") {
        doc.arrays.push_back({parent, e.attrs, {}});
        openArray_ = true;
      }
    }
  }

  bool startsWith(std::string_view p) const { return s_.substr(i_, p.size()) == p; }
  void skipPast(std::string_view end, const char* what) {
    const std::size_t e = s_.find(end, i_);
    if (e == std::string_view::npos) fail(std::string("unterminated ") + what + " (file truncated?)");
    i_ = e + end.size();
  }
  void skipSpace() {
    while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\t' || s_[i_] == '\n' || s_[i_] == '\r')) ++i_;
  }
  void expect(char c) {
    if (i_ >= s_.size()) fail("the file ends inside a tag (file truncated?)");
    if (s_[i_] != c) fail(std::string("malformed tag: expected '") + c + "' at byte " + std::to_string(i_));
    ++i_;
  }
  std::string readName() {
    const std::size_t b = i_;
    while (i_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[i_])) || s_[i_] == '_' || s_[i_] == ':' ||
                              s_[i_] == '-' || s_[i_] == '.'))
      ++i_;
    if (i_ == b) fail("malformed tag at byte " + std::to_string(b));
    return std::string(s_.substr(b, i_ - b));
  }
  void readAttributes(Attributes& attrs, bool& selfClosing) {
    while (true) {
      skipSpace();
      if (i_ >= s_.size()) fail("the file ends inside a tag (file truncated?)");
      if (s_[i_] == '>') {
        ++i_;
        return;
      }
      if (startsWith("/>")) {
        i_ += 2;
        selfClosing = true;
        return;
      }
      const std::string name = readName();
      skipSpace();
      expect('=');
      skipSpace();
      if (i_ >= s_.size() || (s_[i_] != '"' && s_[i_] != '\'')) fail("attribute " + name + " has no quoted value");
      const char quote = s_[i_++];
      const std::size_t e = s_.find(quote, i_);
      if (e == std::string_view::npos) fail("attribute " + name + " is not terminated (file truncated?)");
      attrs[name] = decodeEntities(s_.substr(i_, e - i_), name);
      i_ = e + 1;
    }
  }
  std::string decodeEntities(std::string_view v, const std::string& attr) const {
    std::string out;
    for (std::size_t k = 0; k < v.size(); ++k) {
      if (v[k] != '&') {
        out += v[k];
        continue;
      }
      const std::size_t semi = v.find(';', k);
      if (semi == std::string_view::npos) fail("attribute " + attr + " has a malformed character reference");
      const std::string_view ent = v.substr(k + 1, semi - k - 1);
      if (ent == "amp") out += '&';
      else if (ent == "lt") out += '<';
      else if (ent == "gt") out += '>';
      else if (ent == "quot") out += '"';
      else if (ent == "apos") out += '\'';
      else if (ent.size() > 1 && ent[0] == '#') {
        unsigned code = 0;
        const bool hex = ent[1] == 'x' || ent[1] == 'X';
        const char* b = ent.data() + (hex ? 2 : 1);
        const auto r = std::from_chars(b, ent.data() + ent.size(), code, hex ? 16 : 10);
        if (r.ec != std::errc() || r.ptr != ent.data() + ent.size() || code == 0 || code > 127)
          fail("attribute " + attr + " has an unsupported character reference &" + std::string(ent) + ";");
        out += static_cast<char>(code);
      } else {
        fail("attribute " + attr + " has an unknown entity &" + std::string(ent) + ";");
      }
      k = semi;
    }
    return out;
  }
  [[noreturn]] void fail(const std::string& problem) const { throw InputError(path_, problem); }

  const std::string& path_;
  std::string_view s_;
  std::size_t i_ = 0;
  bool openArray_ = false;  // the last start tag was a kept DataArray: the next text is its values
};

}  // namespace

VtpDocument scanVtpDocument(const std::string& path, std::string_view data) { return Scanner(path, data).parse(); }

}  // namespace reamsim::io
