// NIfTI-1/-2 (.nii, .nii.gz) through vtkNIFTIImageReader, which handles qform/sform and the qfac slice
// flip. Its header is read first (UpdateInformation) and checked against the file before any voxel is
// allocated; every VTK complaint becomes an InputError. World coordinates are NIfTI's RAS.
#include <vtkImageData.h>
#include <vtkMatrix4x4.h>
#include <vtkNIFTIImageHeader.h>
#include <vtkNIFTIImageReader.h>
#include <vtkPointData.h>
#include <vtkDataArray.h>
#include <vtkSmartPointer.h>

#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <new>

#include "Bytes.h"
#include "Geometry.h"
#include "HeaderText.h"
#include "Readers.h"
#include "reamsim/ctimport/VolumeIO.h"
#include "VtkMessages.h"
#include "reamsim/ctimport/Progress.h"
#include "reamsim/mesh/MeshError.h"

namespace reamsim::ct::io {
namespace {

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && lower(s.substr(s.size() - suffix.size())) == suffix;
}

int bytesPerVoxel(int datatype) {
  switch (datatype) {
    case 2: case 256: return 1;     // uint8, int8
    case 4: case 512: return 2;     // int16, uint16
    case 8: case 768: case 16: return 4;  // int32, uint32, float32
    case 64: case 1024: case 1280: return 8;  // float64, int64, uint64
    default: return 0;
  }
}

// The header fields that decide how the voxels are read, in host byte order, NIfTI-1 or -2.
struct Header {
  std::int64_t dim[8] = {};
  int datatype = 0, bitpix = 0;
  double voxOffset = 0;
};


// VTK's reader trusts the header: an unknown datatype crashed it (SIGBUS in vtkNIFTIImageReader::
// RequestInformation, found by fuzzing). So magic, sizes, datatype and vox_offset are read here (through
// zlib, which reads plain and gzip files alike) and checked before VTK sees the file.
Header checkHeader(const std::string& path, bool gz, std::uint64_t size) {
  if (!gz && size < 348) throw InputError(path, "file of " + std::to_string(size) + " bytes is too small for a NIfTI header");
  gzFile f = gzopen(path.c_str(), "rb");
  if (!f) throw InputError(path, "cannot open");
  unsigned char h[540] = {};
  const int n = gzread(f, h, sizeof h);
  gzclose(f);
  if (n < 4) throw InputError(path, gz ? "no NIfTI header in the compressed data (file truncated or not gzip?)"
                                        : "too small for a NIfTI header");
  const std::int32_t le = loadScalar<std::int32_t>(h, false), be = loadScalar<std::int32_t>(h, true);
  const bool v2 = le == 540 || be == 540;
  const bool bigEndian = v2 ? be == 540 : be == 348;
  const int headerBytes = v2 ? 540 : 348;
  if (!v2 && le != 348 && be != 348)
    throw InputError(path, "not a NIfTI file (sizeof_hdr is " + std::to_string(le) + ", expected 348 or 540)");
  if (n < headerBytes)
    throw InputError(path, "the NIfTI header ends after " + std::to_string(n) + " of " + std::to_string(headerBytes) +
                               " bytes (file truncated?)");
  Header r;
  if (v2) {
    if (std::memcmp(h + 4, "n+2", 4) != 0) throw InputError(path, "not a NIfTI-2 file (bad magic)");
    if (std::memcmp(h + 8, "\r\n\032\n", 4) != 0)  // as VTK checks: catches a text-mode transfer
      throw InputError(path, "bytes 8-11 of the NIfTI-2 magic are not \\r\\n\\032\\n (file damaged by a text-mode transfer?)");
    r.datatype = loadScalar<std::int16_t>(h + 12, bigEndian);
    r.bitpix = loadScalar<std::int16_t>(h + 14, bigEndian);
    for (int a = 0; a < 8; ++a) r.dim[a] = loadScalar<std::int64_t>(h + 16 + 8 * std::size_t(a), bigEndian);
    r.voxOffset = double(loadScalar<std::int64_t>(h + 168, bigEndian));
  } else {
    if (std::memcmp(h + 344, "ni1", 4) == 0)
      throw InputError(path, "a .hdr/.img pair header: only single-file NIfTI (.nii, .nii.gz) is supported");
    if (std::memcmp(h + 344, "n+1", 4) != 0) throw InputError(path, "not a NIfTI-1 file (bad magic at byte 344)");
    for (int a = 0; a < 8; ++a) r.dim[a] = loadScalar<std::int16_t>(h + 40 + 2 * std::size_t(a), bigEndian);
    r.datatype = loadScalar<std::int16_t>(h + 70, bigEndian);
    r.bitpix = loadScalar<std::int16_t>(h + 72, bigEndian);
    r.voxOffset = loadScalar<float>(h + 108, bigEndian);
  }

  const std::int64_t nd = r.dim[0];
  if (nd < 3 || nd > 7) throw InputError(path, "dim[0] is " + std::to_string(nd) + "; a CT volume has 3 dimensions");
  for (int a = 1; a <= 3; ++a)
    if (r.dim[a] < 1 || r.dim[a] > 1000000)
      throw InputError(path, "dim[" + std::to_string(a) + "] = " + std::to_string(r.dim[a]) + " is invalid");
  for (int a = 4; a <= nd; ++a)
    if (r.dim[a] > 1 || r.dim[a] < 0)
      throw InputError(path, "dimension " + std::to_string(a) + " has " + std::to_string(r.dim[a]) +
                                 " samples (time series or vector image); a single 3-D volume is required");
  const int bpv = bytesPerVoxel(r.datatype);
  if (bpv == 0) throw InputError(path, "unsupported NIfTI datatype " + std::to_string(r.datatype));
  if (r.bitpix != 8 * bpv)
    throw InputError(path, "bitpix " + std::to_string(r.bitpix) + " does not match datatype " + std::to_string(r.datatype));
  if (!(r.voxOffset >= headerBytes && r.voxOffset <= double(std::uint64_t{1} << 40)) || r.voxOffset != std::floor(r.voxOffset))
    throw InputError(path, "vox_offset " + std::to_string(r.voxOffset) + " is not a byte offset after the " +
                               std::to_string(headerBytes) + "-byte header");
  return r;
}

}  // namespace

CtVolume readNifti(const std::string& path, const ReadTick& tick) {
  const std::uint64_t size = fileSize(path);
  const bool gz = endsWith(path, ".gz");
  const Header header = checkHeader(path, gz, size);
  std::uint64_t voxels = 1;
  for (int a = 1; a <= 3; ++a) voxels *= std::uint64_t(header.dim[a]);
  if (voxels > kMaxVoxels) throw InputError(path, "volume of " + std::to_string(voxels) + " voxels is too large");
  const int bpv = bytesPerVoxel(header.datatype);
  const std::uint64_t dataBytes = voxels * std::uint64_t(bpv);
  const std::uint64_t offset = std::uint64_t(header.voxOffset);
  if (!gz && size < offset + dataBytes)
    throw InputError(path, "holds " + std::to_string(size) + " bytes but the header needs " +
                               std::to_string(offset + dataBytes) + " (vox_offset " + std::to_string(offset) + " + " +
                               std::to_string(dataBytes) + " bytes of voxels): file truncated?");
  if (gz && dataBytes > size * 1100 + 4096)
    throw InputError(path, "header declares " + std::to_string(dataBytes) + " bytes of voxels but the compressed file has only " +
                               std::to_string(size) + " bytes (file truncated or wrong sizes?)");

  VtkMessageCapture capture;
  auto reader = vtkSmartPointer<vtkNIFTIImageReader>::New();
  capture.observe(reader);
  if (!reader->CanReadFile(path.c_str()))
    throw InputError(path, "not a NIfTI file (bad header size or magic)");
  reader->SetFileName(path.c_str());
  reader->UpdateInformation();
  if (capture.anyError()) throw InputError(path, "VTK could not read the NIfTI header: " + capture.firstMessage());
  vtkNIFTIImageHeader* h = reader->GetNIFTIHeader();
  if (!h) throw InputError(path, "VTK could not read the NIfTI header");
  if (tick) capture.observeProgress(reader, tick);
  try {
    reader->Update();
    if (capture.cancelled()) throw ImportCancelled("reading");
  } catch (const std::bad_alloc&) {
    throw InputError(path, "out of memory reading " + std::to_string(voxels) + " voxels");
  }
  if (capture.anyError()) throw InputError(path, "VTK could not read the voxels: " + capture.firstMessage());
  vtkImageData* img = reader->GetOutput();
  vtkDataArray* scalars = img ? img->GetPointData()->GetScalars() : nullptr;
  int ext[6];
  if (img) img->GetExtent(ext);
  if (!scalars || scalars->GetNumberOfComponents() != 1 || std::uint64_t(scalars->GetNumberOfTuples()) != voxels)
    throw InputError(path, "VTK returned no or incomplete voxel data (file truncated?)");

  CtVolume v;
  v.sourcePath = path;
  v.format = "nifti";
  v.space = PatientSpace::RAS;
  for (int a = 0; a < 3; ++a) v.dims[std::size_t(a)] = ext[2 * a + 1] - ext[2 * a] + 1;
  v.values.resize(std::size_t(voxels));
  for (vtkIdType i = 0; i < scalars->GetNumberOfTuples(); ++i) v.values[std::size_t(i)] = float(scalars->GetComponent(i, 0));

  // Rescale (scl_slope = 0 means none).
  const double slope = reader->GetRescaleSlope(), inter = reader->GetRescaleIntercept();
  v.integerValued = h->GetDataType() != 16 && h->GetDataType() != 64;
  if (slope != 0 && (slope != 1 || inter != 0)) {
    for (float& x : v.values) x = float(x * slope + inter);
    v.integerValued = v.integerValued && slope == std::floor(slope) && inter == std::floor(inter);
    v.notes.push_back("scl_slope " + std::to_string(slope) + ", scl_inter " + std::to_string(inter) + " applied");
  }

  // Units: xyzt_units & 7 = 1 metre, 2 mm, 3 micron, 0 unknown (mm assumed).
  double unit = 1.0;
  switch (h->GetXYZTUnits() & 7) {
    case 1: unit = 1000.0; v.notes.push_back("spatial unit metre: scaled ×1000 to mm"); break;
    case 3: unit = 0.001; v.notes.push_back("spatial unit micron: scaled ×0.001 to mm"); break;
    case 0: v.notes.push_back("spatial unit not given: mm assumed"); break;
    default: break;
  }
  double spacing[3], vtkOrigin[3];
  img->GetSpacing(spacing);
  img->GetOrigin(vtkOrigin);
  // sform when set (nibabel's choice), else qform, else pixdim only (NIfTI "method 1").
  vtkMatrix4x4* m = nullptr;
  if (h->GetSFormCode() > 0) m = reader->GetSFormMatrix();
  if (!m && h->GetQFormCode() > 0) m = reader->GetQFormMatrix();
  std::array<Vec3, 3> steps;
  for (int a = 0; a < 3; ++a) {
    Vec3 s;
    for (int r = 0; r < 3; ++r) s[r] = (m ? m->GetElement(r, a) : (r == a ? 1.0 : 0.0)) * spacing[a] * unit;
    steps[std::size_t(a)] = s;
  }
  setAxesFromSteps(v, steps, path, 0);
  Vec3 o;
  for (int r = 0; r < 3; ++r) {
    double x = m ? m->GetElement(r, 3) : 0.0;
    for (int c = 0; c < 3; ++c) x += (m ? m->GetElement(r, c) : (r == c ? 1.0 : 0.0)) * vtkOrigin[c];
    o[r] = x * unit;
  }
  v.origin = o;
  if (!m) {
    v.space = PatientSpace::Unspecified;
    v.notes.push_back("neither sform nor qform is set: axes aligned, origin 0, patient frame unknown");
  } else if (reader->GetQFac() < 0) {
    v.notes.push_back("qfac -1: slices reversed to a right-handed index order");
  }
  return v;
}

}  // namespace reamsim::ct::io
