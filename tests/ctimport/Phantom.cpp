#include "Phantom.h"

#include <vtkDICOMCTGenerator.h>
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
                      const std::string& transferSyntax) {
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
  writer->SetFilePattern("%s/IM-%04d.dcm");
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

}  // namespace phantom
