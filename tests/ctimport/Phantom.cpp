#include "Phantom.h"

#include <vtkDICOMCTGenerator.h>
#include <vtkDICOMDictHash.h>
#include <vtkDICOMMetaData.h>
#include <vtkDICOMParser.h>
#include <vtkDICOMSCGenerator.h>
#include <vtkDICOMWriter.h>
#include <vtkImageData.h>
#include <vtkMatrix4x4.h>
#include <vtkShortArray.h>
#include <vtkUnsignedShortArray.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace phantom {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::string num(double x) {
  char b[64];
  std::snprintf(b, sizeof b, "%.17g", x);
  return b;
}

std::int16_t toShort(float v) { return std::int16_t(std::lround(v)); }

template <class T>
void put(std::string& out, T v, bool bigEndian = false) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (bigEndian)
    for (std::size_t k = 0; k < sizeof(T) / 2; ++k) std::swap(b[k], b[sizeof(T) - 1 - k]);
  out.append(b, sizeof(T));
}

std::string int16Bytes(const std::vector<float>& hu, std::size_t from = 0, std::size_t count = SIZE_MAX) {
  std::string out;
  const std::size_t end = std::min(hu.size(), from + std::min(count, hu.size()));
  for (std::size_t i = from; i < end; ++i) put(out, toShort(hu[i]));
  return out;
}

std::string zlibCompress(const std::string& raw) {
  uLongf size = compressBound(uLong(raw.size()));
  std::string out(size, '\0');
  if (compress2(reinterpret_cast<Bytef*>(out.data()), &size, reinterpret_cast<const Bytef*>(raw.data()), uLong(raw.size()),
                6) != Z_OK)
    throw std::runtime_error("zlib compress failed");
  out.resize(size);
  return out;
}

void writeGzip(const std::string& path, const std::string& raw) {
  gzFile f = gzopen(path.c_str(), "wb");
  if (!f) throw std::runtime_error("cannot write " + path);
  const int n = gzwrite(f, raw.data(), unsigned(raw.size()));
  gzclose(f);
  if (n != int(raw.size())) throw std::runtime_error("gzwrite failed for " + path);
}

// "(x,y,z)" of the scaled axis vectors, optionally in RAS (x, y negated).
std::string nrrdDirections(const Grid& g, bool ras) {
  std::string s;
  for (int a = 0; a < 3; ++a) {
    Vec3 v = g.axis(a) * g.spacing[std::size_t(a)];
    if (ras) v = {-v.x, -v.y, v.z};
    s += (a ? " (" : "(") + num(v.x) + "," + num(v.y) + "," + num(v.z) + ")";
  }
  return s;
}

std::string nrrdOrigin(const Grid& g, bool ras) {
  const Vec3 o = ras ? Vec3{-g.origin.x, -g.origin.y, g.origin.z} : g.origin;
  return "(" + num(o.x) + "," + num(o.y) + "," + num(o.z) + ")";
}

std::string sizes(const Grid& g) {
  return std::to_string(g.dims[0]) + " " + std::to_string(g.dims[1]) + " " + std::to_string(g.dims[2]);
}

std::string metaHeader(const Grid& g, bool compressed, std::size_t compressedSize, const std::string& dataFile) {
  std::ostringstream h;
  h << "ObjectType = Image\nNDims = 3\nBinaryData = True\nBinaryDataByteOrderMSB = False\n"
    << "CompressedData = " << (compressed ? "True" : "False") << "\n";
  if (compressed) h << "CompressedDataSize = " << compressedSize << "\n";
  h << "TransformMatrix =";
  for (int a = 0; a < 3; ++a)
    for (int r = 0; r < 3; ++r) h << " " << num(g.direction[std::size_t(3 * r + a)]);  // axis a's cosines
  h << "\nOffset = " << num(g.origin.x) << " " << num(g.origin.y) << " " << num(g.origin.z) << "\n"
    << "CenterOfRotation = 0 0 0\nAnatomicalOrientation = RAI\n"
    << "ElementSpacing = " << num(g.spacing[0]) << " " << num(g.spacing[1]) << " " << num(g.spacing[2]) << "\n"
    << "DimSize = " << sizes(g) << "\nElementType = MET_SHORT\nElementDataFile = " << dataFile << "\n";
  return h.str();
}

}  // namespace

Vec3 Grid::world(double i, double j, double k) const {
  const double x = i * spacing[0], y = j * spacing[1], z = k * spacing[2];
  return origin + axis(0) * x + axis(1) * y + axis(2) * z;
}

bool SphereAndCylinder::insideMain(const Vec3& p) const {
  const Vec3 d = p - center;
  if (reamsim::squaredNorm(d) <= sphereRadius * sphereRadius) return true;
  const double along = reamsim::dot(d, axis);
  return std::abs(along) <= cylinderLength / 2 && reamsim::squaredNorm(d - axis * along) <= cylinderRadius * cylinderRadius;
}

bool SphereAndCylinder::inside(const Vec3& p) const {
  return insideMain(p) || (fragment && reamsim::squaredNorm(p - fragmentCenter) <= fragmentRadius * fragmentRadius);
}

double SphereAndCylinder::mainVolume() const {
  const double r2 = cylinderRadius * cylinderRadius;
  return kPi * r2 * cylinderLength + 4.0 / 3.0 * kPi * std::pow(sphereRadius * sphereRadius - r2, 1.5);
}

double SphereAndCylinder::fragmentVolume() const { return 4.0 / 3.0 * kPi * std::pow(fragmentRadius, 3); }

std::array<double, 9> rotation(const Vec3& axisIn, double degrees) {
  const Vec3 u = reamsim::normalized(axisIn);
  const double t = degrees * kPi / 180, c = std::cos(t), s = std::sin(t), C = 1 - c;
  return {c + u.x * u.x * C,       u.x * u.y * C - u.z * s, u.x * u.z * C + u.y * s,
          u.y * u.x * C + u.z * s, c + u.y * u.y * C,       u.y * u.z * C - u.x * s,
          u.z * u.x * C - u.y * s, u.z * u.y * C + u.x * s, c + u.z * u.z * C};
}

Grid gridAround(const Vec3& center, double radius, const std::array<double, 3>& spacing,
                const std::array<double, 9>& direction) {
  Grid g;
  g.spacing = spacing;
  g.direction = direction;
  for (int a = 0; a < 3; ++a) g.dims[std::size_t(a)] = int(std::ceil(2 * radius / spacing[std::size_t(a)])) + 1;
  // Centre the grid on `center`.
  const Vec3 half = g.world((g.dims[0] - 1) / 2.0, (g.dims[1] - 1) / 2.0, (g.dims[2] - 1) / 2.0);
  g.origin = center - half;
  return g;
}

std::vector<float> sample(const Grid& g, const Solid& solid, float tissue, float bone, int n) {
  std::vector<float> out(g.voxels());
  std::size_t idx = 0;
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i, ++idx) {
        int in = 0;
        for (int c = 0; c < n; ++c)
          for (int b = 0; b < n; ++b)
            for (int a = 0; a < n; ++a)
              in += solid(g.world(i - 0.5 + (a + 0.5) / n, j - 0.5 + (b + 0.5) / n, k - 0.5 + (c + 0.5) / n));
        out[idx] = tissue + (bone - tissue) * float(in) / float(n * n * n);
      }
  return out;
}

void writeBytes(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), std::streamsize(bytes.size()));
  if (!out) throw std::runtime_error("cannot write " + path);
}

std::string readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void writeNrrd(const std::string& path, const Grid& g, const std::vector<float>& hu) {
  std::string h = "NRRD0004\n# written by the ReamSim CT-import test\ntype: short\ndimension: 3\n"
                  "space: left-posterior-superior\nsizes: " + sizes(g) + "\nspace directions: " +
                  nrrdDirections(g, false) + "\nkinds: domain domain domain\nendian: little\nencoding: raw\n"
                  "space origin: " + nrrdOrigin(g, false) + "\n\n";
  writeBytes(path, h + int16Bytes(hu));
}

void writeNrrdDetachedGzipRas(const std::string& nhdr, const Grid& g, const std::vector<float>& hu) {
  const std::string dataName = std::filesystem::path(nhdr).stem().string() + ".raw.gz";
  std::string h = "NRRD0005\ntype: float\ndimension: 3\nspace: RAS\nsizes: " + sizes(g) +
                  "\nspace directions: " + nrrdDirections(g, true) + "\nendian: big\nencoding: gzip\n"
                  "space origin: " + nrrdOrigin(g, true) + "\ndata file: " + dataName + "\n";
  writeBytes(nhdr, h);
  std::string raw;
  for (float v : hu) put(raw, v, true);
  writeGzip((std::filesystem::path(nhdr).parent_path() / dataName).string(), raw);
}

void writeNrrdSlices(const std::string& nhdr, const Grid& g, const std::vector<float>& hu) {
  std::string h = "NRRD0004\ntype: int16\ndimension: 3\nspace: LPS\nsizes: " + sizes(g) +
                  "\nspace directions: " + nrrdDirections(g, false) + "\nendian: little\nencoding: raw\n"
                  "space origin: " + nrrdOrigin(g, false) + "\ndata file: slice%03d.raw 0 " +
                  std::to_string(g.dims[2] - 1) + " 1\n";
  writeBytes(nhdr, h);
  const std::size_t plane = std::size_t(g.dims[0]) * g.dims[1];
  const std::filesystem::path dir = std::filesystem::path(nhdr).parent_path();
  for (int k = 0; k < g.dims[2]; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "slice%03d.raw", k);
    writeBytes((dir / name).string(), int16Bytes(hu, plane * std::size_t(k), plane));
  }
}

void writeMha(const std::string& path, const Grid& g, const std::vector<float>& hu, bool compressed) {
  const std::string raw = int16Bytes(hu);
  const std::string data = compressed ? zlibCompress(raw) : raw;
  writeBytes(path, metaHeader(g, compressed, data.size(), "LOCAL") + data);
}

void writeMhdRaw(const std::string& mhd, const Grid& g, const std::vector<float>& hu) {
  const std::string rawName = std::filesystem::path(mhd).stem().string() + ".raw";
  writeBytes(mhd, metaHeader(g, false, 0, rawName));
  writeBytes((std::filesystem::path(mhd).parent_path() / rawName).string(), int16Bytes(hu));
}

void writeNifti(const std::string& path, const Grid& g, const std::vector<float>& hu) {
  std::string h(352, '\0');
  const auto at = [&](std::size_t offset, auto value) { std::memcpy(&h[offset], &value, sizeof(value)); };
  at(0, std::int32_t(348));
  at(40, std::int16_t(3));
  for (int a = 0; a < 3; ++a) at(42 + 2 * std::size_t(a), std::int16_t(g.dims[std::size_t(a)]));
  for (int a = 3; a < 7; ++a) at(42 + 2 * std::size_t(a), std::int16_t(1));
  at(70, std::int16_t(512));  // NIFTI_TYPE_UINT16
  at(72, std::int16_t(16));
  at(76, float(1));  // qfac
  for (int a = 0; a < 3; ++a) at(80 + 4 * std::size_t(a), float(g.spacing[std::size_t(a)]));
  at(108, float(352));  // vox_offset
  at(112, float(1));    // scl_slope
  at(116, float(-1024));  // scl_inter: stored = HU + 1024
  at(123, char(2));     // xyzt_units: mm
  at(252, std::int16_t(0));  // qform_code
  at(254, std::int16_t(1));  // sform_code: scanner
  // sform rows: RAS = F · (D · diag(s) · ijk + origin), F = diag(-1, -1, 1).
  for (int r = 0; r < 3; ++r) {
    const double sign = r < 2 ? -1 : 1;
    for (int c = 0; c < 3; ++c)
      at(280 + 16 * std::size_t(r) + 4 * std::size_t(c), float(sign * g.direction[std::size_t(3 * r + c)] * g.spacing[std::size_t(c)]));
    at(280 + 16 * std::size_t(r) + 12, float(sign * g.origin[r]));
  }
  std::memcpy(&h[344], "n+1\0", 4);
  std::string data;
  for (float v : hu) put(data, std::uint16_t(std::lround(v + 1024)));
  if (path.size() > 3 && path.compare(path.size() - 3, 3, ".gz") == 0) writeGzip(path, h + data);
  else writeBytes(path, h + data);
}

void writeDicomSeries(const std::string& directory, const Grid& g, const std::vector<float>& hu,
                      const std::string& transferSyntax, const std::string& filePattern) {
  std::filesystem::create_directories(directory);
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(g.dims[0], g.dims[1], g.dims[2]);
  image->SetSpacing(g.spacing[0], g.spacing[1], g.spacing[2]);
  auto values = vtkSmartPointer<vtkShortArray>::New();
  values->SetNumberOfValues(vtkIdType(hu.size()));
  for (std::size_t i = 0; i < hu.size(); ++i) values->SetValue(vtkIdType(i), toShort(hu[i]));
  image->GetPointData()->SetScalars(values);
  auto matrix = vtkSmartPointer<vtkMatrix4x4>::New();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) matrix->SetElement(r, c, g.direction[std::size_t(3 * r + c)]);
    matrix->SetElement(r, 3, g.origin[r]);
  }
  auto generator = vtkSmartPointer<vtkDICOMCTGenerator>::New();
  auto writer = vtkSmartPointer<vtkDICOMWriter>::New();
  writer->SetInputData(image);
  writer->SetGenerator(generator);
  writer->SetPatientMatrix(matrix);
  writer->SetMemoryRowOrderToFileNative();
  writer->SetSeriesDescription("ReamSim phantom");
  writer->SetFilePrefix(directory.c_str());
  writer->SetFilePattern(filePattern.c_str());
  if (!transferSyntax.empty()) writer->SetTransferSyntaxUID(transferSyntax.c_str());
  writer->Write();
  if (writer->GetErrorCode() != 0) throw std::runtime_error("vtkDICOMWriter failed in " + directory);
}

void writeDicomMultiFrame(const std::string& path, const Grid& g, const std::vector<float>& hu) {
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(g.dims[0], g.dims[1], g.dims[2]);
  image->SetSpacing(g.spacing[0], g.spacing[1], g.spacing[2]);
  auto values = vtkSmartPointer<vtkUnsignedShortArray>::New();
  values->SetNumberOfValues(vtkIdType(hu.size()));
  for (std::size_t i = 0; i < hu.size(); ++i) values->SetValue(vtkIdType(i), std::uint16_t(std::clamp(std::lround(hu[i]) + 1024, 0L, 65535L)));
  image->GetPointData()->SetScalars(values);
  auto generator = vtkSmartPointer<vtkDICOMSCGenerator>::New();
  generator->MultiFrameOn();
  auto writer = vtkSmartPointer<vtkDICOMWriter>::New();
  writer->SetInputData(image);
  writer->SetGenerator(generator);
  writer->SetFileDimensionality(3);
  writer->SetFileName(path.c_str());
  writer->Write();
  if (writer->GetErrorCode() != 0 || !std::filesystem::exists(path)) throw std::runtime_error("vtkDICOMWriter failed on " + path);
}

namespace {
// Explicit VR little endian elements for the DICOMDIR writer.
void putU16(std::string& b, std::uint16_t v) { put(b, v); }
void putU32(std::string& b, std::uint32_t v) { put(b, v); }
void putTag(std::string& b, std::uint16_t group, std::uint16_t element) { putU16(b, group), putU16(b, element); }
// A short-VR element; the value padded to an even length (UI with a NUL, text with a space).
void putText(std::string& b, std::uint16_t group, std::uint16_t element, const char* vr, std::string value) {
  if (value.size() % 2) value.push_back(std::string(vr) == "UI" ? '\0' : ' ');
  putTag(b, group, element);
  b.append(vr, 2);
  putU16(b, std::uint16_t(value.size()));
  b += value;
}
void putUL(std::string& b, std::uint16_t group, std::uint16_t element, std::uint32_t v) {
  putTag(b, group, element);
  b += "UL";
  putU16(b, 4);
  putU32(b, v);
}
void putUS(std::string& b, std::uint16_t group, std::uint16_t element, std::uint16_t v) {
  putTag(b, group, element);
  b += "US";
  putU16(b, 2);
  putU16(b, v);
}

struct DirFile {
  std::string id;  // components joined by '\\'
  std::string sopClass, sopInstance, syntax, study, series, patientName, patientId, instance;
};
}  // namespace

void writeDicomDir(const std::string& root, const std::vector<std::string>& files) {
  std::vector<DirFile> entries;
  for (const std::string& f : files) {
    auto meta = vtkSmartPointer<vtkDICOMMetaData>::New();
    auto parser = vtkSmartPointer<vtkDICOMParser>::New();
    const std::string path = (std::filesystem::path(root) / f).string();
    parser->SetFileName(path.c_str());
    parser->SetMetaData(meta);
    parser->Update();
    if (parser->GetErrorCode() != 0) throw std::runtime_error("writeDicomDir: cannot parse " + path);
    DirFile e;
    e.id = f;
    std::replace(e.id.begin(), e.id.end(), '/', '\\');
    e.sopClass = meta->Get(DC::SOPClassUID).AsString();
    e.sopInstance = meta->Get(DC::SOPInstanceUID).AsString();
    e.syntax = meta->Get(DC::TransferSyntaxUID).AsString();
    e.study = meta->Get(DC::StudyInstanceUID).AsString();
    e.series = meta->Get(DC::SeriesInstanceUID).AsString();
    e.patientName = meta->Get(DC::PatientName).AsString();
    e.patientId = meta->Get(DC::PatientID).AsString();
    e.instance = meta->Get(DC::InstanceNumber).AsString();
    entries.push_back(e);
  }
  // Records in order: for each series, PATIENT (only before the first), STUDY and SERIES once, then its images.
  // Offsets (of each record's item, from the start of the file) are fixed-size, so the layout is computed with
  // zeros first and the records are written again with the right values.
  struct Record {
    std::string type;
    std::size_t file = 0;      // entries[file] for the fields
    std::size_t lower = 0;     // index of the first record one level down (0: none)
    std::size_t next = 0;      // index of the next record on this level (0: none)
  };
  std::vector<Record> records{{"PATIENT", 0, 1, 0}};
  std::size_t lastSeriesRecord = 0, lastStudyRecord = 0;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const bool newStudy = i == 0 || entries[i].study != entries[i - 1].study;
    const bool newSeries = newStudy || entries[i].series != entries[i - 1].series;
    if (newStudy) {
      if (lastStudyRecord) records[lastStudyRecord].next = records.size();
      lastStudyRecord = records.size();
      records.push_back({"STUDY", i, records.size() + 1, 0});
    }
    if (newSeries) {
      if (lastSeriesRecord && !newStudy) records[lastSeriesRecord].next = records.size();
      lastSeriesRecord = records.size();
      records.push_back({"SERIES", i, records.size() + 1, 0});
    } else {
      records.back().next = records.size();
    }
    records.push_back({"IMAGE", i, 0, 0});
  }
  auto recordBytes = [&](const Record& r, const std::vector<std::uint32_t>& offset) {
    const DirFile& e = entries[r.file];
    std::string b;
    putUL(b, 0x0004, 0x1400, r.next ? offset[r.next] : 0);
    putUS(b, 0x0004, 0x1410, 0xFFFF);
    putUL(b, 0x0004, 0x1420, r.lower ? offset[r.lower] : 0);
    putText(b, 0x0004, 0x1430, "CS", r.type);
    if (r.type == "IMAGE") {
      putText(b, 0x0004, 0x1500, "CS", e.id);
      putText(b, 0x0004, 0x1510, "UI", e.sopClass);
      putText(b, 0x0004, 0x1511, "UI", e.sopInstance);
      putText(b, 0x0004, 0x1512, "UI", e.syntax);
      putText(b, 0x0020, 0x0013, "IS", e.instance);
    } else if (r.type == "SERIES") {
      putText(b, 0x0008, 0x0060, "CS", "CT");
      putText(b, 0x0020, 0x000E, "UI", e.series);
      putText(b, 0x0020, 0x0011, "IS", "1");
    } else if (r.type == "STUDY") {
      putText(b, 0x0008, 0x0020, "DA", "20260101");
      putText(b, 0x0008, 0x0030, "TM", "120000");
      putText(b, 0x0020, 0x000D, "UI", e.study);
      putText(b, 0x0020, 0x0010, "SH", "1");
    } else {
      putText(b, 0x0010, 0x0010, "PN", e.patientName);
      putText(b, 0x0010, 0x0020, "LO", e.patientId.empty() ? "PHANTOM" : e.patientId);
    }
    return b;
  };
  std::string meta;  // group 2 after its group length
  putTag(meta, 0x0002, 0x0001);
  meta += "OB";
  putU16(meta, 0);
  putU32(meta, 2);
  meta += std::string("\0\1", 2);
  putText(meta, 0x0002, 0x0002, "UI", "1.2.840.10008.1.3.10");  // Media Storage Directory Storage
  putText(meta, 0x0002, 0x0003, "UI", "1.2.826.0.1.3680043.2.1125.1.1");
  putText(meta, 0x0002, 0x0010, "UI", "1.2.840.10008.1.2.1");
  putText(meta, 0x0002, 0x0012, "UI", "1.2.826.0.1.3680043.2.1125.1");
  std::string head(128, '\0');
  head += "DICM";
  putUL(head, 0x0002, 0x0000, std::uint32_t(meta.size()));
  head += meta;
  auto layout = [&](const std::vector<std::uint32_t>& offset) {
    std::string b = head;
    putText(b, 0x0004, 0x1130, "CS", "REAMSIM");
    putUL(b, 0x0004, 0x1200, offset[0]);
    putUL(b, 0x0004, 0x1202, offset[0]);
    putUS(b, 0x0004, 0x1212, 0);
    putTag(b, 0x0004, 0x1220);
    b += "SQ";
    putU16(b, 0);
    putU32(b, 0xFFFFFFFF);
    std::vector<std::uint32_t> at;
    for (const Record& r : records) {
      at.push_back(std::uint32_t(b.size()));
      const std::string body = recordBytes(r, offset);
      putTag(b, 0xFFFE, 0xE000);
      putU32(b, std::uint32_t(body.size()));
      b += body;
    }
    putTag(b, 0xFFFE, 0xE0DD);
    putU32(b, 0);
    return std::make_pair(b, at);
  };
  const auto first = layout(std::vector<std::uint32_t>(records.size(), 0));
  writeBytes((std::filesystem::path(root) / "DICOMDIR").string(), layout(first.second).first);
}

}  // namespace phantom
