// MetaImage (ITK/MetaIO) reader: .mha (header and data in one file) and .mhd (data in ElementDataFile, a
// LIST of slice files or a numbered pattern), raw or zlib-compressed. Own parser rather than
// vtkMetaImageReader, which ignores TransformMatrix and reports errors only on the console.
// World coordinates of MetaImage are LPS (ITK's convention); TransformMatrix lists the direction cosines
// of the i, j, k axes one after the other (ITK writes direction column by column).
#include <cmath>
#include <map>

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

SampleType parseElementType(const std::string& path, const Field& f) {
  static const std::map<std::string, SampleType> types = {
      {"MET_CHAR", SampleType::Int8},        {"MET_UCHAR", SampleType::UInt8},
      {"MET_SHORT", SampleType::Int16},      {"MET_USHORT", SampleType::UInt16},
      {"MET_INT", SampleType::Int32},        {"MET_UINT", SampleType::UInt32},
      {"MET_LONG", SampleType::Int32},       {"MET_ULONG", SampleType::UInt32},
      {"MET_LONG_LONG", SampleType::Int64},  {"MET_ULONG_LONG", SampleType::UInt64},
      {"MET_FLOAT", SampleType::Float32},    {"MET_DOUBLE", SampleType::Float64}};
  const auto it = types.find(f.value);
  if (it == types.end()) throw InputError(path, f.line, "unsupported ElementType '" + f.value + "'");
  return it->second;
}

}  // namespace

CtVolume readMetaImage(const std::string& path, const ReadTick& tick) {
  const std::string bytes = readWholeFile(path);
  std::map<std::string, Field> fields;  // keys lower-cased
  std::size_t pos = 0, dataStart = std::string::npos;
  long lineNo = 0;
  std::vector<std::pair<std::string, long>> listed;
  bool inList = false;
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
    if (trim(line).empty()) continue;
    const std::size_t eq = line.find('=');
    if (eq == std::string::npos) {
      if (lineNo == 1) throw InputError(path, 1, "not a MetaImage header (expected 'Key = Value' lines)");
      throw InputError(path, lineNo, "expected 'Key = Value', found '" + line.substr(0, 60) + "'");
    }
    const std::string key = lower(trim(line.substr(0, eq)));
    if (fields.count(key)) throw InputError(path, lineNo, "key '" + trim(line.substr(0, eq)) + "' appears twice");
    fields[key] = Field{trim(line.substr(eq + 1)), lineNo};
    if (key == "elementdatafile") {
      // ElementDataFile is always the last key: the data (LOCAL) or the file list follows.
      const std::string value = lower(fields[key].value);
      if (value.rfind("list", 0) == 0) inList = true;
      else {
        dataStart = pos;
        break;
      }
    }
    if (lineNo > 1000) throw InputError(path, "no ElementDataFile within the first 1000 header lines");
  }
  const auto find = [&](const char* key) -> const Field* {
    const auto it = fields.find(key);
    return it == fields.end() ? nullptr : &it->second;
  };
  const auto require = [&](const char* key, const char* display) -> const Field& {
    const Field* f = find(key);
    if (!f) throw InputError(path, std::string("the MetaImage header has no ") + display + " (file truncated or not MetaImage?)");
    return *f;
  };

  CtVolume v;
  v.sourcePath = path;
  v.format = "metaimage";
  v.space = PatientSpace::LPS;

  if (const Field* ot = find("objecttype"))
    if (lower(ot->value) != "image") throw InputError(path, ot->line, "ObjectType is '" + ot->value + "', not Image");
  const Field& nd = require("ndims", "NDims");
  if (parseInteger(path, nd.line, nd.value, "NDims") != 3)
    throw InputError(path, nd.line, "NDims is " + nd.value + "; a CT volume has 3 dimensions");
  const Field& ds = require("dimsize", "DimSize");
  const std::vector<double> dims = parseNumbers(path, ds.line, ds.value, 3, "DimSize");
  for (int a = 0; a < 3; ++a) {
    if (dims[std::size_t(a)] != std::floor(dims[std::size_t(a)]) || dims[std::size_t(a)] < 1 || dims[std::size_t(a)] > 1e9)
      throw InputError(path, ds.line, "DimSize must be three positive integers");
    v.dims[std::size_t(a)] = int(dims[std::size_t(a)]);
  }
  const std::uint64_t total = std::uint64_t(v.dims[0]) * std::uint64_t(v.dims[1]) * std::uint64_t(v.dims[2]);
  if (total > kMaxVoxels) throw InputError(path, ds.line, "volume of " + std::to_string(total) + " voxels is too large");
  if (const Field* ch = find("elementnumberofchannels"))
    if (parseInteger(path, ch->line, ch->value, "ElementNumberOfChannels") != 1)
      throw InputError(path, ch->line, "multi-channel images are not CT volumes");
  if (const Field* bd = find("binarydata"))
    if (!parseBool(path, bd->line, bd->value, "BinaryData"))
      throw InputError(path, bd->line, "ASCII MetaImage data (BinaryData = False) is not supported");

  PayloadSpec spec;
  spec.header = path;
  spec.type = parseElementType(path, require("elementtype", "ElementType"));
  const Field* msb = find("binarydatabyteordermsb");
  if (!msb) msb = find("elementbyteordermsb");
  if (msb) spec.bigEndian = parseBool(path, msb->line, msb->value, "BinaryDataByteOrderMSB");
  bool compressed = false;
  if (const Field* c = find("compresseddata")) compressed = parseBool(path, c->line, c->value, "CompressedData");
  spec.encoding = compressed ? Encoding::Deflate : Encoding::Raw;

  // Geometry. ElementSpacing is the sample pitch; ElementSize (physical voxel size) is the fallback.
  const Field* sp = find("elementspacing");
  if (!sp) sp = find("elementsize");
  std::array<double, 3> spacing{1, 1, 1};
  if (sp) {
    const std::vector<double> s = parseNumbers(path, sp->line, sp->value, 3, "ElementSpacing");
    for (int a = 0; a < 3; ++a) spacing[std::size_t(a)] = s[std::size_t(a)];
  } else {
    v.notes.push_back("the header gives no ElementSpacing; 1 mm assumed along each axis");
  }
  std::array<double, 9> cols{1, 0, 0, 0, 1, 0, 0, 0, 1};  // axis 0 cosines, axis 1, axis 2
  const Field* tm = find("transformmatrix");
  if (!tm) tm = find("rotation");
  if (!tm) tm = find("orientation");
  if (tm) {
    const std::vector<double> m = parseNumbers(path, tm->line, tm->value, 9, "TransformMatrix");
    for (int i = 0; i < 9; ++i) cols[std::size_t(i)] = m[std::size_t(i)];
  }
  std::array<Vec3, 3> steps;
  for (int a = 0; a < 3; ++a) {
    if (!(spacing[std::size_t(a)] > 0) || !std::isfinite(spacing[std::size_t(a)]))
      throw InputError(path, sp ? sp->line : 0, "ElementSpacing must be three positive numbers");
    steps[std::size_t(a)] = Vec3{cols[std::size_t(3 * a)], cols[std::size_t(3 * a + 1)], cols[std::size_t(3 * a + 2)]};
    const double n = norm(steps[std::size_t(a)]);
    if (!(n > 0)) throw InputError(path, tm ? tm->line : 0, "TransformMatrix has a zero axis");
    steps[std::size_t(a)] = steps[std::size_t(a)] * (spacing[std::size_t(a)] / n);
  }
  setAxesFromSteps(v, steps, path, tm ? tm->line : 0);
  const Field* off = find("offset");
  if (!off) off = find("position");
  if (!off) off = find("origin");
  if (off) {
    const std::vector<double> o = parseNumbers(path, off->line, off->value, 3, "Offset");
    v.origin = {o[0], o[1], o[2]};
  }
  if (const Field* ao = find("anatomicalorientation")) v.notes.push_back("AnatomicalOrientation " + ao->value);

  // Data.
  const Field& df = require("elementdatafile", "ElementDataFile");
  long headerSize = 0;
  if (const Field* hs = find("headersize")) headerSize = parseInteger(path, hs->line, hs->value, "HeaderSize");
  if (headerSize < -1) throw InputError(path, "HeaderSize must be ≥ -1");
  if (headerSize != 0 && compressed) throw InputError(path, "HeaderSize with CompressedData is not supported");
  std::uint64_t compressedSize = 0;
  if (const Field* cs = find("compresseddatasize")) {
    const long c = parseInteger(path, cs->line, cs->value, "CompressedDataSize");
    if (c < 0) throw InputError(path, cs->line, "CompressedDataSize must be ≥ 0");
    compressedSize = std::uint64_t(c);
  }
  std::vector<std::string> files;
  const std::vector<std::string> w = splitWords(df.value);
  if (w.empty()) throw InputError(path, df.line, "ElementDataFile is empty");
  if (lower(w[0]) == "local") {
    PayloadPart part;
    part.path = path;
    part.inMemory = std::string_view(bytes).substr(std::min(dataStart, bytes.size()));
    if (part.inMemory.empty()) throw InputError(path, "no voxel data after the header (file truncated?)");
    part.samples = std::size_t(total);
    part.compressedBytes = compressedSize;
    spec.parts.push_back(part);
  } else {
    if (lower(w[0]) == "list") {
      for (const auto& [name, line] : listed) files.push_back(besideHeader(path, name));
      if (files.empty()) throw InputError(path, df.line, "ElementDataFile = LIST is followed by no file names");
    } else if (w.size() >= 4 && w[0].find('%') != std::string::npos) {
      for (long number : numberedFileSequence(path, df.line, w[1], w[2], w[3], "ElementDataFile"))
        files.push_back(besideHeader(path, formatNumbered(path, w[0], number)));
    } else {
      files.push_back(besideHeader(path, df.value));
    }
    if (total % files.size() != 0 || (total / files.size()) % (std::uint64_t(v.dims[0]) * v.dims[1]) != 0)
      throw InputError(path, df.line, std::to_string(files.size()) + " data files cannot each hold whole slices");
    for (const std::string& f : files) {
      PayloadPart part;
      part.path = f;
      part.samples = std::size_t(total / files.size());
      part.byteSkip = headerSize > 0 ? std::uint64_t(headerSize) : 0;
      part.dataAtEnd = headerSize == -1 && !compressed;
      part.compressedBytes = files.size() == 1 ? compressedSize : 0;
      part.oneOfMany = files.size() > 1;
      spec.parts.push_back(part);
    }
  }
  checkPayloadSizes(spec);
  readPayload(spec, v.values, v.notes, tick);  // sizes v.values once the data are read
  v.integerValued = isIntegerSample(spec.type);
  return v;
}

}  // namespace reamsim::ct::io
