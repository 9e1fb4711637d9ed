#include "reamsim/ctimport/VolumeIO.h"

#include <filesystem>
#include <fstream>

#include "HeaderText.h"
#include "Readers.h"
#include "SlantedSlices.h"
#include "reamsim/mesh/MeshError.h"

namespace reamsim::ct {
namespace {

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && io::lower(s.substr(s.size() - suffix.size())) == suffix;
}

// DICOM Part 10 files have "DICM" after a 128-byte preamble.
bool hasDicomPreamble(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char buf[132] = {};
  return in.read(buf, 132) && std::string(buf + 128, 4) == "DICM";
}

}  // namespace

std::string detectVolumeFormat(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return "dicom";
  if (endsWith(path, ".nrrd") || endsWith(path, ".nhdr")) return "nrrd";
  if (endsWith(path, ".mha") || endsWith(path, ".mhd")) return "metaimage";
  if (endsWith(path, ".nii") || endsWith(path, ".nii.gz")) return "nifti";
  if (endsWith(path, ".dcm") || endsWith(path, ".dicom") || endsWith(path, ".ima")) return "dicom";
  if (std::filesystem::is_regular_file(path, ec) && hasDicomPreamble(path)) return "dicom";
  return "";
}

std::vector<std::string> supportedVolumeExtensions() {
  return {".nrrd", ".nhdr", ".mha", ".mhd", ".nii", ".nii.gz", ".dcm"};
}

CtVolume readVolume(const std::string& path, const ProgressCallback& progress) {
  const io::ReadTick tick = [&](double f) { return !progress || progress(f, "reading"); };
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(path, "file or directory not found");
  const std::string format = detectVolumeFormat(path);
  CtVolume v;
  if (format == "nrrd") v = io::readNrrd(path, tick);
  else if (format == "metaimage") v = io::readMetaImage(path, tick);
  else if (format == "nifti") v = io::readNifti(path, tick);
  else if (format == "dicom") v = io::readDicom(path, tick);
  else
    throw InputError(path, "unknown volume format (expected a DICOM directory or file, .nrrd, .nhdr, .mha, .mhd, "
                           ".nii or .nii.gz)");
  v.sourcePath = path;
  if (!io::resampleSlantedSlices(v, [&] { return tick(1.0); })) throw ImportCancelled("reading");
  checkVolume(v);
  if (!tick(1.0)) throw ImportCancelled("reading");
  return v;
}

}  // namespace reamsim::ct
