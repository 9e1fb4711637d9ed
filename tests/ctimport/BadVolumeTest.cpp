// Bad volumes (truncated, wrong header, missing slices, inconsistent spacing, lying sizes) end in an
// InputError that names the file and says what is wrong — never a crash, a hang or a huge allocation.
#include <gtest/gtest.h>

#include <vtkDICOMMetaData.h>
#include <vtkDICOMParser.h>
#include <vtkDICOMValue.h>
#include <vtkSmartPointer.h>

#include <sys/resource.h>

#include <algorithm>
#include <random>
#include <cstring>
#include <fstream>

#include "Phantom.h"
#include "TestUtil.h"
#include "reamsim/ctimport/VolumeIO.h"
#include "reamsim/mesh/MeshError.h"

namespace {

using namespace reamsim;
using cttest::fs::path;

struct Small {
  phantom::Grid grid = phantom::gridAround({0, 0, 0}, 6, {1, 1, 1.5}, phantom::rotation({0, 0, 1}, 0));
  std::vector<float> hu = phantom::sample(grid, [](const Vec3& p) { return norm(p) < 4; }, 40, 1200, 1);
};

// Expects readVolume(p) to throw an InputError whose message names `file` and contains `problem`.
void expectInputError(const std::string& p, const std::string& file, const std::string& problem) {
  try {
    ct::readVolume(p);
    ADD_FAILURE() << p << ": no error, expected '" << problem << "'";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(file), std::string::npos) << what;
    EXPECT_NE(what.find(problem), std::string::npos) << what;
  }
}

void truncate(const std::string& p, std::size_t keep) {
  std::string b = phantom::readBytes(p);
  phantom::writeBytes(p, b.substr(0, std::min(keep, b.size())));
}

std::string replaceOnce(std::string s, const std::string& from, const std::string& to) {
  const std::size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) s.replace(at, from.size(), to);
  return s;
}

TEST(BadVolumes, MissingAndUnknownFiles) {
  const path d = cttest::scratch("bad_missing");
  expectInputError((d / "nope.nrrd").string(), "nope.nrrd", "not found");
  phantom::writeBytes((d / "x.vol").string(), "whatever");
  expectInputError((d / "x.vol").string(), "x.vol", "unknown volume format");
  expectInputError(d.string(), d.string(), "no DICOM image series");  // empty directory
}

TEST(BadVolumes, NrrdTruncatedWrongHeaderAndMissingSliceFiles) {
  const Small s;
  const path d = cttest::scratch("bad_nrrd");
  const std::string good = (d / "good.nrrd").string();
  phantom::writeNrrd(good, s.grid, s.hu);
  const std::string bytes = phantom::readBytes(good);

  const std::string cut = (d / "cut.nrrd").string();
  phantom::writeBytes(cut, bytes.substr(0, bytes.size() - 100));
  expectInputError(cut, "cut.nrrd", "file truncated");

  const std::string magic = (d / "magic.nrrd").string();
  phantom::writeBytes(magic, "NRRX" + bytes.substr(4));
  expectInputError(magic, "magic.nrrd", "not a NRRD file");

  const std::string noSizes = (d / "nosizes.nrrd").string();
  phantom::writeBytes(noSizes, replaceOnce(bytes, "sizes:", "sizez:"));
  expectInputError(noSizes, "nosizes.nrrd", "no 'sizes' field");

  const std::string badType = (d / "type.nrrd").string();
  phantom::writeBytes(badType, replaceOnce(bytes, "type: short", "type: quaternion"));
  expectInputError(badType, "type.nrrd:3:", "unsupported sample type");

  const std::string dims2 = (d / "dim2.nrrd").string();
  phantom::writeBytes(dims2, replaceOnce(bytes, "dimension: 3", "dimension: 2"));
  expectInputError(dims2, "dim2.nrrd", "a CT volume has 3");

  // Header claims a volume far larger than the data: refused before allocating 2^34 voxels.
  const std::string huge = (d / "huge.nrrd").string();
  const std::string sizesLine = "sizes: " + std::to_string(s.grid.dims[0]) + " " + std::to_string(s.grid.dims[1]) +
                                " " + std::to_string(s.grid.dims[2]);
  phantom::writeBytes(huge, replaceOnce(bytes, sizesLine, "sizes: 2048 2048 4096"));
  expectInputError(huge, "huge.nrrd", "too large");
  const std::string lying = (d / "lying.nrrd").string();
  phantom::writeBytes(lying, replaceOnce(bytes, sizesLine, "sizes: 512 512 400"));
  expectInputError(lying, "lying.nrrd", "expected for");

  const std::string sheared = (d / "sheared.nrrd").string();
  phantom::writeBytes(sheared, replaceOnce(bytes, "space directions: (1,0,0)", "space directions: (1,0.5,0)"));
  expectInputError(sheared, "sheared.nrrd", "not perpendicular");

  // Slice files: one missing, one short.
  const std::string nhdr = (d / "slices.nhdr").string();
  phantom::writeNrrdSlices(nhdr, s.grid, s.hu);
  cttest::fs::remove(d / "slice004.raw");
  expectInputError(nhdr, "slice004.raw", "missing slice file");
  phantom::writeNrrdSlices(nhdr, s.grid, s.hu);
  truncate((d / "slice002.raw").string(), 10);
  expectInputError(nhdr, "slice002.raw", "file truncated");
}

// Found by fuzzing (session 26): numbered file patterns whose min, max or step overflowed the arithmetic
// (SIGFPE on LONG_MIN / -1), and compressed data that was allocated for at its declared size before a byte of
// it was inflated.
TEST(BadVolumes, NumberedFilePatternsOutOfRange) {
  const path d = cttest::scratch("bad_pattern");
  const std::string nrrd = (d / "seq.nhdr").string();
  phantom::writeBytes(nrrd, "NRRD0004\ntype: short\ndimension: 3\nsizes: 4 4 4\nspacings: 1 1 1\nencoding: raw\n"
                            "endian: little\ndata file: x%d 0 -9223372036854775808 -1\n");
  expectInputError(nrrd, "seq.nhdr:8:", "data file: min, max and step must lie within");
  const std::string mhd = (d / "seq.mhd").string();
  phantom::writeBytes(mhd, "ObjectType = Image\nNDims = 3\nDimSize = 4 4 4\nElementType = MET_SHORT\n"
                           "ElementDataFile = x%d -9223372036854775808 9223372036854775807 1\n");
  expectInputError(mhd, "seq.mhd:5:", "ElementDataFile: min, max and step must lie within");
}

long peakRssKb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

TEST(BadVolumes, GarbageCompressedDataAllocatesNothingForItsDeclaredSize) {
  const path d = cttest::scratch("bad_gzip");
  std::string garbage(500000, '\0');
  std::mt19937 rng(7);
  for (char& c : garbage) c = char(rng());
  // 256 M voxels declared (1 GiB of floats; within what zlib could expand 0.5 MB to), 0.5 MB of random bytes given.
  const std::string nrrd = (d / "garbage.nrrd").string();
  phantom::writeBytes(nrrd, "NRRD0004\ntype: short\ndimension: 3\nsizes: 1024 1024 256\nspacings: 1 1 1\n"
                            "encoding: gzip\nendian: little\n\n" + garbage);
  const std::string mha = (d / "garbage.mha").string();
  phantom::writeBytes(mha, "ObjectType = Image\nNDims = 3\nDimSize = 1024 1024 256\nElementType = MET_SHORT\n"
                           "CompressedData = True\nElementDataFile = LOCAL\n" + garbage);
  const long before = peakRssKb();
  expectInputError(nrrd, "garbage.nrrd", "corrupt compressed data");
  expectInputError(mha, "garbage.mha", "corrupt compressed data");
  EXPECT_LT(peakRssKb() - before, 100 * 1024) << "kB of peak memory more after reading two 0.5 MB files";
}

TEST(BadVolumes, MetaImageTruncatedWrongHeaderAndCorruptCompression) {
  const Small s;
  const path d = cttest::scratch("bad_mha");
  const std::string good = (d / "good.mha").string();
  phantom::writeMha(good, s.grid, s.hu, false);
  const std::string bytes = phantom::readBytes(good);

  const std::string cut = (d / "cut.mha").string();
  phantom::writeBytes(cut, bytes.substr(0, bytes.size() / 2));
  expectInputError(cut, "cut.mha", "file truncated");

  const std::string dims = (d / "dims.mha").string();
  phantom::writeBytes(dims, replaceOnce(bytes, "DimSize = ", "DimSize = 7 "));
  expectInputError(dims, "dims.mha:", "DimSize: expected 3 numbers");

  const std::string type = (d / "type.mha").string();
  phantom::writeBytes(type, replaceOnce(bytes, "MET_SHORT", "MET_COMPLEX"));
  expectInputError(type, "type.mha:", "unsupported ElementType");

  const std::string header = (d / "header.mha").string();
  phantom::writeBytes(header, "this is not\na MetaImage\n");
  expectInputError(header, "header.mha:1:", "not a MetaImage header");

  const std::string zipped = (d / "zipped.mha").string();
  phantom::writeMha(zipped, s.grid, s.hu, true);
  std::string z = phantom::readBytes(zipped);
  for (std::size_t i = z.size() - 40; i < z.size() - 20; ++i) z[i] = char(z[i] ^ 0x5A);  // corrupt the stream
  phantom::writeBytes(zipped, z);
  expectInputError(zipped, "zipped.mha", "compressed data");

  const std::string mhd = (d / "v.mhd").string();
  phantom::writeMhdRaw(mhd, s.grid, s.hu);
  cttest::fs::remove(d / "v.raw");
  expectInputError(mhd, "v.raw", "not found");
}

TEST(BadVolumes, NiftiTruncatedAndWrongHeader) {
  const Small s;
  const path d = cttest::scratch("bad_nifti");
  const std::string nii = (d / "v.nii").string();
  phantom::writeNifti(nii, s.grid, s.hu);
  const std::string bytes = phantom::readBytes(nii);

  const std::string cut = (d / "cut.nii").string();
  phantom::writeBytes(cut, bytes.substr(0, 352 + 100));
  expectInputError(cut, "cut.nii", "file truncated");

  const std::string tiny = (d / "tiny.nii").string();
  phantom::writeBytes(tiny, bytes.substr(0, 100));
  expectInputError(tiny, "tiny.nii", "too small for a NIfTI header");

  std::string wrong = bytes;
  wrong[0] = 'X';  // sizeof_hdr no longer 348
  const std::string bad = (d / "bad.nii").string();
  phantom::writeBytes(bad, wrong);
  expectInputError(bad, "bad.nii", "not a NIfTI file (sizeof_hdr is 344");

  std::string timeSeries = bytes;
  const std::int16_t four = 4, five = 5;
  std::memcpy(&timeSeries[40], &four, 2);
  std::memcpy(&timeSeries[48], &five, 2);
  const std::string ts = (d / "ts.nii").string();
  phantom::writeBytes(ts, timeSeries);
  expectInputError(ts, "ts.nii", "time series");

  // A compressed file cut in the middle of the voxels (noise so that it does not compress to nothing).
  const phantom::Grid big = phantom::gridAround({0, 0, 0}, 15, {1, 1, 1}, phantom::rotation({0, 0, 1}, 0));
  std::vector<float> noise(big.voxels());
  std::uint32_t state = 7;
  for (float& x : noise) x = float((state = state * 1664525u + 1013904223u) >> 20) - 1024;
  const std::string gz = (d / "v.nii.gz").string();
  phantom::writeNifti(gz, big, noise);
  truncate(gz, phantom::readBytes(gz).size() / 2);
  expectInputError(gz, "v.nii.gz", "could not read");
  truncate(gz, 60);
  expectInputError(gz, "v.nii.gz", "truncated");
}

// The positions of the slices of a DICOM series decide whether they form one regular volume.
TEST(BadVolumes, DicomMissingSliceInconsistentSpacingAndTruncatedFile) {
  const Small s;
  const path d = cttest::scratch("bad_dicom");
  phantom::writeDicomSeries((d / "ok").string(), s.grid, s.hu);
  ASSERT_NO_THROW(ct::readVolume((d / "ok").string()));

  phantom::writeDicomSeries((d / "gap").string(), s.grid, s.hu);
  cttest::fs::remove(d / "gap" / "IM-0004.dcm");
  expectInputError((d / "gap").string(), "gap", "missing slice: gap of 3 mm");

  // Move one slice by a third of the spacing, editing ImagePositionPatient's text in the file.
  phantom::writeDicomSeries((d / "uneven").string(), s.grid, s.hu);
  const std::string file = (d / "uneven" / "IM-0003.dcm").string();
  auto parser = vtkSmartPointer<vtkDICOMParser>::New();
  auto meta = vtkSmartPointer<vtkDICOMMetaData>::New();
  parser->SetMetaData(meta);
  parser->SetFileName(file.c_str());
  parser->Update();
  const std::string ipp = meta->Get(DC::ImagePositionPatient).AsString();
  const std::size_t lastSep = ipp.rfind('\\');
  ASSERT_NE(lastSep, std::string::npos) << ipp;
  const double z = std::stod(ipp.substr(lastSep + 1));
  std::string moved = ipp.substr(0, lastSep + 1) + std::to_string(z + 0.5).substr(0, ipp.size() - lastSep - 1);
  moved.resize(ipp.size(), ' ');
  phantom::writeBytes(file, replaceOnce(phantom::readBytes(file), ipp, moved));
  expectInputError((d / "uneven").string(), "uneven", "inconsistent slice spacing");

  phantom::writeDicomSeries((d / "cut").string(), s.grid, s.hu);
  truncate((d / "cut" / "IM-0005.dcm").string(), 700);
  EXPECT_THROW(ct::readVolume((d / "cut").string()), InputError);
  truncate((d / "cut" / "IM-0005.dcm").string(), 100);
  EXPECT_THROW(ct::readVolume((d / "cut").string()), InputError);
}

}  // namespace
