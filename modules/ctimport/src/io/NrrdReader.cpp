// NRRD (teem) reader: attached (.nrrd) and detached (.nhdr) headers, data in one file, a LIST of files or a
// numbered pattern ("data file: quarter.%d 1 93 1"), raw / gzip / ascii encodings. Own parser rather than
// vtkNrrdReader, which ignores "space directions" orientation and prints instead of failing on bad input.
#include <cctype>
#include <cmath>
#include <map>
#include <optional>

#include "Bytes.h"
#include "Geometry.h"
#include "HeaderText.h"
#include "Payload.h"
#include "Readers.h"
#include "reamsim/ctimport/VolumeIO.h"
#include "reamsim/mesh/MeshError.h"

namespace reamsim::ct::io {
namespace {

using Field = HeaderField;

SampleType parseType(const std::string& path, const Field& f) {
  static const std::map<std::string, SampleType> types = {
      {"signed char", SampleType::Int8}, {"int8", SampleType::Int8}, {"int8_t", SampleType::Int8},
      {"uchar", SampleType::UInt8}, {"unsigned char", SampleType::UInt8}, {"uint8", SampleType::UInt8},
      {"uint8_t", SampleType::UInt8}, {"short", SampleType::Int16}, {"short int", SampleType::Int16},
      {"signed short", SampleType::Int16}, {"signed short int", SampleType::Int16}, {"int16", SampleType::Int16},
      {"int16_t", SampleType::Int16}, {"ushort", SampleType::UInt16}, {"unsigned short", SampleType::UInt16},
      {"unsigned short int", SampleType::UInt16}, {"uint16", SampleType::UInt16}, {"uint16_t", SampleType::UInt16},
      {"int", SampleType::Int32}, {"signed int", SampleType::Int32}, {"int32", SampleType::Int32},
      {"int32_t", SampleType::Int32}, {"uint", SampleType::UInt32}, {"unsigned int", SampleType::UInt32},
      {"uint32", SampleType::UInt32}, {"uint32_t", SampleType::UInt32}, {"longlong", SampleType::Int64},
      {"long long", SampleType::Int64}, {"long long int", SampleType::Int64}, {"signed long long", SampleType::Int64},
      {"signed long long int", SampleType::Int64}, {"int64", SampleType::Int64}, {"int64_t", SampleType::Int64},
      {"ulonglong", SampleType::UInt64}, {"unsigned long long", SampleType::UInt64},
      {"unsigned long long int", SampleType::UInt64}, {"uint64", SampleType::UInt64}, {"uint64_t", SampleType::UInt64},
      {"float", SampleType::Float32}, {"double", SampleType::Float64}};
  const auto it = types.find(lower(f.value));
  if (it == types.end()) throw InputError(path, f.line, "unsupported sample type '" + f.value + "'");
  return it->second;
}

// "(a,b,c)" vectors and "none", separated by whitespace.
std::vector<std::optional<Vec3>> parseVectors(const std::string& path, const Field& f, std::size_t count,
                                              const std::string& what) {
  std::vector<std::optional<Vec3>> out;
  const std::string& s = f.value;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
    if (i >= s.size()) break;
    if (s[i] == '(') {
      const std::size_t close = s.find(')', i);
      if (close == std::string::npos) throw InputError(path, f.line, what + ": missing ')'");
      std::string inner = s.substr(i + 1, close - i - 1);
      for (char& c : inner)
        if (c == ',') c = ' ';
      const std::vector<double> v = parseNumbers(path, f.line, inner, 3, what);
      out.emplace_back(Vec3{v[0], v[1], v[2]});
      i = close + 1;
    } else if (lower(s.substr(i, 4)) == "none") {
      out.emplace_back(std::nullopt);
      i += 4;
    } else {
      throw InputError(path, f.line, what + ": expected '(x,y,z)' or 'none'");
    }
  }
  if (out.size() != count)
    throw InputError(path, f.line, what + ": expected " + std::to_string(count) + " entries, found " +
                                       std::to_string(out.size()));
  return out;
}

}  // namespace

CtVolume readNrrd(const std::string& path, const ReadTick& tick) {
  const std::string bytes = readWholeFile(path);
  if (bytes.compare(0, 7, "NRRD000") != 0 || bytes.size() < 8)
    throw InputError(path, 1, "not a NRRD file (the first line must be 'NRRD000X')");

  std::map<std::string, Field> fields;
  std::vector<std::pair<std::string, long>> listed;  // "data file: LIST" names
  std::size_t pos = bytes.find('\n');
  pos = pos == std::string::npos ? bytes.size() : pos + 1;
  long lineNo = 1;
  bool inList = false;
  std::size_t dataStart = std::string::npos;
  while (pos < bytes.size()) {
    const std::size_t nl = bytes.find('\n', pos);
    std::string line = bytes.substr(pos, (nl == std::string::npos ? bytes.size() : nl) - pos);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    pos = nl == std::string::npos ? bytes.size() : nl + 1;
    ++lineNo;
    if (inList) {
      if (!trim(line).empty()) listed.emplace_back(trim(line), lineNo);
      continue;
    }
    if (trim(line).empty()) {
      dataStart = pos;
      break;
    }
    if (line[0] == '#') continue;
    if (line.find(":=") != std::string::npos) continue;  // key/value pairs: free-form metadata
    const std::size_t colon = line.find(": ");
    if (colon == std::string::npos)
      throw InputError(path, lineNo, "expected 'field: value' in the NRRD header, found '" + line.substr(0, 60) + "'");
    std::string key = lower(trim(line.substr(0, colon)));
    if (key == "datafile") key = "data file";
    if (key == "centerings") key = "centers";
    if (fields.count(key)) throw InputError(path, lineNo, "field '" + key + "' appears twice");
    fields[key] = Field{trim(line.substr(colon + 2)), lineNo};
    if (key == "data file" && lower(fields[key].value.substr(0, 4)) == "list") inList = true;
  }
  const auto require = [&](const char* key) -> const Field& {
    const auto it = fields.find(key);
    if (it == fields.end()) throw InputError(path, std::string("the NRRD header has no '") + key + "' field");
    return it->second;
  };
  const auto find = [&](const char* key) -> const Field* {
    const auto it = fields.find(key);
    return it == fields.end() ? nullptr : &it->second;
  };

  CtVolume v;
  v.sourcePath = path;
  v.format = "nrrd";

  const Field& dimF = require("dimension");
  const long dimension = parseInteger(path, dimF.line, dimF.value, "dimension");
  if (dimension != 3 && dimension != 4)
    throw InputError(path, dimF.line, "NRRD has " + std::to_string(dimension) + " dimensions; a CT volume has 3");
  const SampleType type = parseType(path, require("type"));
  const Field& sizesF = require("sizes");
  const std::vector<double> sizesD = parseNumbers(path, sizesF.line, sizesF.value, std::size_t(dimension), "sizes");
  std::vector<long> sizes;
  for (double s : sizesD) {
    if (s != std::floor(s) || s < 1 || s > 1e9) throw InputError(path, sizesF.line, "sizes must be positive integers");
    sizes.push_back(long(s));
  }
  // A 4-D header is accepted only with a single-sample non-spatial axis (e.g. a 1-component "vector").
  int dropped = -1;
  if (dimension == 4) {
    if (sizes[0] == 1) dropped = 0;
    else if (sizes[3] == 1) dropped = 3;
    else
      throw InputError(path, sizesF.line, "4-D NRRD (time series or vector image) is not a single CT volume");
  }
  std::vector<int> spatial;
  for (int a = 0; a < dimension; ++a)
    if (a != dropped) spatial.push_back(a);
  for (int a = 0; a < 3; ++a) v.dims[a] = int(sizes[std::size_t(spatial[std::size_t(a)])]);
  const std::uint64_t total = std::uint64_t(v.dims[0]) * std::uint64_t(v.dims[1]) * std::uint64_t(v.dims[2]);
  if (total > kMaxVoxels) throw InputError(path, sizesF.line, "volume of " + std::to_string(total) + " voxels is too large");

  if (const Field* k = find("kinds")) {
    const std::vector<std::string> kinds = splitWords(k->value);
    if (kinds.size() != std::size_t(dimension))
      throw InputError(path, k->line, "kinds: expected " + std::to_string(dimension) + " entries");
    for (int a : spatial) {
      const std::string kind = lower(kinds[std::size_t(a)]);
      if (kind != "domain" && kind != "space" && kind != "???" && kind != "none")
        throw InputError(path, k->line, "axis " + std::to_string(a) + " is of kind '" + kinds[std::size_t(a)] +
                                            "', not a spatial axis; only scalar 3-D volumes are supported");
    }
  }

  // Encoding and byte order.
  PayloadSpec spec;
  spec.header = path;
  spec.type = type;
  const Field& encF = require("encoding");
  const std::string enc = lower(encF.value);
  if (enc == "raw") spec.encoding = Encoding::Raw;
  else if (enc == "gzip" || enc == "gz") spec.encoding = Encoding::Deflate;
  else if (enc == "ascii" || enc == "text" || enc == "txt") spec.encoding = Encoding::Ascii;
  else throw InputError(path, encF.line, "unsupported encoding '" + encF.value + "' (supported: raw, gzip, ascii)");
  if (sampleSize(type) > 1 && spec.encoding != Encoding::Ascii) {
    const Field& endF = require("endian");
    const std::string e = lower(endF.value);
    if (e != "little" && e != "big") throw InputError(path, endF.line, "endian must be 'little' or 'big'");
    spec.bigEndian = e == "big";
  }

  // Patient space.
  bool flipY = false;  // LAS → LPS
  if (const Field* s = find("space")) {
    const std::string sp = lower(s->value);
    if (sp == "left-posterior-superior" || sp == "lps") v.space = PatientSpace::LPS;
    else if (sp == "right-anterior-superior" || sp == "ras") v.space = PatientSpace::RAS;
    else if (sp == "left-anterior-superior" || sp == "las") {
      v.space = PatientSpace::LPS;
      flipY = true;
      v.notes.push_back("space LAS converted to LPS (y negated)");
    } else if (sp == "scanner-xyz" || sp == "3d-right-handed" || sp == "3d-left-handed") {
      v.space = PatientSpace::Unspecified;
      v.notes.push_back("space '" + s->value + "' names no anatomical frame; coordinates kept as written");
    } else {
      throw InputError(path, s->line, "unsupported space '" + s->value + "'");
    }
  }
  if (const Field* sd = find("space dimension")) {
    if (parseInteger(path, sd->line, sd->value, "space dimension") != 3)
      throw InputError(path, sd->line, "space dimension must be 3");
  }
  double unitScale = 1.0;
  if (const Field* u = find("space units")) {
    std::string units = u->value;
    for (char& c : units)
      if (c == '"') c = ' ';
    const std::vector<std::string> words = splitWords(units);
    for (const std::string& w : words) {
      const std::string lw = lower(w);
      if (lw == "mm" || lw == "millimeter" || lw == "millimeters" || lw == "millimetre" || lw == "millimetres") continue;
      if (lw == "m" || lw == "meter" || lw == "meters" || lw == "metre" || lw == "metres") unitScale = 1000;
      else if (lw == "cm") unitScale = 10;
      else throw InputError(path, u->line, "unsupported space unit '" + w + "' (expected mm)");
    }
    if (unitScale != 1.0) v.notes.push_back("space units scaled ×" + std::to_string(int(unitScale)) + " to mm");
  }

  // Geometry: "space directions" (orientation + spacing) or "spacings" (axis-aligned).
  if (const Field* sd = find("space directions")) {
    const auto vecs = parseVectors(path, *sd, std::size_t(dimension), "space directions");
    std::array<Vec3, 3> steps;
    for (int a = 0; a < 3; ++a) {
      const auto& vec = vecs[std::size_t(spatial[std::size_t(a)])];
      if (!vec) throw InputError(path, sd->line, "space directions: spatial axis " + std::to_string(a) + " is 'none'");
      steps[std::size_t(a)] = *vec * unitScale;
      if (flipY) steps[std::size_t(a)].y = -steps[std::size_t(a)].y;
    }
    setAxesFromSteps(v, steps, path, sd->line);
  } else if (const Field* sp = find("spacings")) {
    const std::vector<std::string> words = splitWords(sp->value);
    if (words.size() != std::size_t(dimension))
      throw InputError(path, sp->line, "spacings: expected " + std::to_string(dimension) + " numbers");
    for (int a = 0; a < 3; ++a) {
      const double s = parseNumber(path, sp->line, words[std::size_t(spatial[std::size_t(a)])], "spacings");
      if (!(s > 0) || !std::isfinite(s))
        throw InputError(path, sp->line, "spacings: axis " + std::to_string(a) + " spacing must be positive");
      v.spacing[std::size_t(a)] = s * unitScale;
    }
  } else {
    v.notes.push_back("the header gives no spacing; 1 mm assumed along each axis");
  }
  if (const Field* so = find("space origin")) {
    const auto o = parseVectors(path, *so, 1, "space origin");
    if (!o[0]) throw InputError(path, so->line, "space origin is 'none'");
    v.origin = *o[0] * unitScale;
    if (flipY) v.origin.y = -v.origin.y;
  }

  // Data files.
  long byteSkip = 0, lineSkip = 0;
  if (const Field* b = find("byte skip")) byteSkip = parseInteger(path, b->line, b->value, "byte skip");
  if (const Field* l = find("line skip")) lineSkip = parseInteger(path, l->line, l->value, "line skip");
  if (byteSkip < -1 || lineSkip < 0) throw InputError(path, "byte skip must be ≥ -1 and line skip ≥ 0");
  if (byteSkip == -1 && spec.encoding != Encoding::Raw)
    throw InputError(path, "'byte skip: -1' is only allowed with raw encoding");

  std::vector<std::string> files;
  const Field* df = find("data file");
  if (!df) {
    if (dataStart == std::string::npos)
      throw InputError(path, "no 'data file' field and no blank line before attached data (detached header "
                             "without data, or truncated file?)");
  } else if (lower(df->value.substr(0, 4)) == "list") {
    for (const auto& [name, line] : listed) files.push_back(besideHeader(path, name));
    if (files.empty()) throw InputError(path, df->line, "'data file: LIST' is followed by no file names");
  } else {
    const std::vector<std::string> w = splitWords(df->value);
    if (w.size() >= 4 && w[0].find('%') != std::string::npos) {
      for (long number : numberedFileSequence(path, df->line, w[1], w[2], w[3], "data file"))
        files.push_back(besideHeader(path, formatNumbered(path, w[0], number)));
    } else {
      files.push_back(besideHeader(path, df->value));
    }
  }

  if (files.empty()) {
    PayloadPart part;
    part.path = path;
    part.inMemory = std::string_view(bytes).substr(dataStart);
    if (part.inMemory.empty())
      throw InputError(path, "no voxel data after the header (file truncated?)");
    part.byteSkip = byteSkip > 0 ? std::uint64_t(byteSkip) : 0;
    part.dataAtEnd = byteSkip == -1;
    part.lineSkip = lineSkip;
    part.samples = std::size_t(total);
    spec.parts.push_back(part);
  } else {
    if (total % files.size() != 0 || (total / files.size()) % (std::uint64_t(v.dims[0]) * v.dims[1]) != 0)
      throw InputError(path, df->line, std::to_string(files.size()) + " data files cannot each hold whole slices of a " +
                                           std::to_string(v.dims[0]) + "×" + std::to_string(v.dims[1]) + "×" +
                                           std::to_string(v.dims[2]) + " volume");
    for (const std::string& f : files) {
      PayloadPart part;
      part.path = f;
      part.byteSkip = byteSkip > 0 ? std::uint64_t(byteSkip) : 0;
      part.dataAtEnd = byteSkip == -1;
      part.lineSkip = lineSkip;
      part.samples = std::size_t(total / files.size());
      part.oneOfMany = files.size() > 1;
      spec.parts.push_back(part);
    }
  }

  checkPayloadSizes(spec);
  readPayload(spec, v.values, v.notes, tick);  // sizes v.values once the data are read
  v.integerValued = isIntegerSample(type);
  return v;
}

}  // namespace reamsim::ct::io
