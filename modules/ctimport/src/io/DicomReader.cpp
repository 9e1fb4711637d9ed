// DICOM series through vtk-dicom (Debian libvtk-dicom-dev, built with GDCM for compressed transfer
// syntaxes). The series is found with vtkDICOMDirectory; before reading voxels, the slice positions are
// checked here (vtk-dicom would silently stack slices with gaps): equal orientation and size, no duplicate
// positions, uniform spacing — a gap of n spacings is reported as n-1 missing slices. World coordinates are
// DICOM patient coordinates (LPS); CT values are rescaled to HU.
#include <vtkDICOMCTRectifier.h>
#include <vtkDICOMDirectory.h>
#include <vtkDICOMMetaData.h>
#include <vtkDICOMReader.h>
#include <vtkDICOMTag.h>
#include <vtkDICOMUtilities.h>
#include <vtkDICOMValue.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkIntArray.h>
#include <vtkMatrix4x4.h>
#include <vtkPointData.h>
#include <vtkInformation.h>
#include <vtkSmartPointer.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkStringArray.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <new>
#include <set>

#include "Bytes.h"
#include "DicomCheck.h"
#include "Geometry.h"
#include "Readers.h"
#include "VtkMessages.h"
#include "reamsim/ctimport/Progress.h"
#include "reamsim/ctimport/VolumeIO.h"
#include "reamsim/mesh/MeshError.h"

namespace reamsim::ct::io {
namespace {

// Smaller tilts (a step within 1.7e-4 of the normal) are within what the axes' perpendicularity check accepts.
constexpr double kTiltToRectifyDegrees = 0.01;
// Scanners tilt the gantry by at most about ±30°; beyond this the positions are wrong, and resampling them
// would make a volume many times the series' size.
constexpr double kMaxTiltDegrees = 45;
// How far a slice may lie off the straight line of in-plane shifts: positions are written to 0.01 mm or so,
// and a quarter of a pixel does not show.
constexpr double kInPlaneToleranceMm = 0.05, kInPlaneTolerancePixels = 0.25;

namespace fs = std::filesystem;

std::string mm(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3g", x);
  return b;
}

// The DICOM files of a folder, each with a sound element structure (DicomCheck.h) or not: vtk-dicom may
// only parse the sound ones. Hidden files are left out, as vtkDICOMDirectory leaves them.
struct FolderFiles {
  std::vector<std::string> sound;
  std::vector<std::pair<std::string, std::string>> broken;  // file, problem
  bool dicomdir = false;  // a DICOMDIR (a CD's index, which points into subfolders)
};

std::string structureProblem(const std::string& file) {
  try {
    return dicomStructureProblem(readWholeFile(file));
  } catch (const InputError& e) {
    return e.what();
  }
}

FolderFiles checkFolder(const std::string& dir, bool recursive) {
  FolderFiles out;
  std::error_code ec;
  auto visit = [&](const fs::directory_entry& e) {
    const std::string name = e.path().filename().string();
    if (name.empty() || name[0] == '.' || !e.is_regular_file(ec)) return;
    const std::string file = e.path().string();
    if (!vtkDICOMUtilities::IsDICOMFile(file.c_str())) return;
    out.dicomdir |= name == "DICOMDIR";
    const std::string problem = structureProblem(file);
    if (problem.empty()) out.sound.push_back(file);
    else out.broken.emplace_back(file, problem);
  };
  if (recursive) {
    for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
      if (it.depth() < 8) visit(*it);
  } else {
    for (const auto& e : fs::directory_iterator(dir, ec)) visit(e);
  }
  std::sort(out.sound.begin(), out.sound.end());
  std::sort(out.broken.begin(), out.broken.end());
  return out;
}

// "; IM-0006.dcm was left out: <problem>" (and how many more), for messages about a series with a gap.
std::string leftOut(const std::vector<std::pair<std::string, std::string>>& broken) {
  if (broken.empty()) return "";
  std::string s = "; " + fs::path(broken[0].first).filename().string() + " was left out: " + broken[0].second;
  if (broken.size() > 1) s += " (and " + std::to_string(broken.size() - 1) + " more broken file(s))";
  return s;
}

// The files of the series to read: all of a directory's largest series, or the series holding `path`.
// Files with a broken structure are left out (noted, and named where a gap shows), the chosen file must not
// be one. A folder with a DICOMDIR is read through it, as vtk-dicom does, and then every DICOM file below the
// folder must be sound: the index may point at any of them.
std::vector<std::string> seriesFiles(const std::string& path, std::vector<std::string>& notes, FolderFiles& folder) {
  std::error_code ec;
  const bool isDir = fs::is_directory(path, ec);
  if (!isDir && !fs::is_regular_file(path, ec)) throw InputError(path, "file or directory not found");
  const std::string parent = isDir ? path : fs::path(path).parent_path().string();
  const std::string dir = parent.empty() ? "." : parent;  // a bare file name lies in the working folder
  folder = checkFolder(dir, false);
  if (folder.dicomdir) {
    folder = checkFolder(dir, true);
    if (!folder.broken.empty()) {
      const bool index = fs::path(folder.broken[0].first).filename() == "DICOMDIR";
      throw InputError(folder.broken[0].first,
                       folder.broken[0].second + (index ? " (the folder's index; open the folder of the series' files instead)"
                                                        : " (a file of the DICOMDIR's folder; move it out, or open the folder "
                                                          "of the series' files)"));
    }
  }
  if (!isDir) {
    const std::string wanted = fs::weakly_canonical(path, ec).string();
    for (const auto& [file, problem] : folder.broken)
      if (fs::weakly_canonical(file, ec).string() == wanted) throw InputError(path, problem);
  }
  for (const auto& [file, problem] : folder.broken)
    notes.push_back("left out " + fs::path(file).filename().string() + ": " + problem);
  VtkMessageCapture capture;
  auto finder = vtkSmartPointer<vtkDICOMDirectory>::New();
  capture.observe(finder);
  if (folder.dicomdir) {
    finder->SetDirectoryName(dir.c_str());
    finder->SetScanDepth(1);
  } else {
    auto names = vtkSmartPointer<vtkStringArray>::New();
    for (const std::string& f : folder.sound) names->InsertNextValue(f);
    finder->SetInputFileNames(names);
  }
  finder->RequirePixelDataOn();
  if (!folder.sound.empty()) finder->Update();
  const int n = folder.sound.empty() ? 0 : finder->GetNumberOfSeries();
  if (n == 0)
    throw InputError(path, (isDir ? "no DICOM image series found in the directory"
                                  : "not a readable DICOM image file (or no image series beside it)") +
                               leftOut(folder.broken));
  if (folder.dicomdir) {
    // The index decides what is read; DICOM files below the folder that it does not list are not, so say so.
    std::set<std::string> listed;
    for (int s = 0; s < n; ++s) {
      vtkStringArray* files = finder->GetFileNamesForSeries(s);
      for (vtkIdType i = 0; i < files->GetNumberOfValues(); ++i)
        listed.insert(fs::weakly_canonical(fs::path(std::string(files->GetValue(i))), ec).string());
    }
    std::size_t unlisted = 0;
    std::string firstUnlisted;
    for (const std::string& f : folder.sound)
      if (fs::path(f).filename() != "DICOMDIR" && !listed.count(fs::weakly_canonical(f, ec).string()) && unlisted++ == 0)
        firstUnlisted = fs::relative(f, dir, ec).string();
    if (unlisted > 0)
      notes.push_back(std::to_string(unlisted) + " DICOM file(s) below the folder are not among the images its DICOMDIR lists (" +
                      firstUnlisted + (unlisted > 1 ? ", …" : "") + ") and were not read");
  }
  int chosen = -1;
  if (!isDir) {
    const std::string wanted = fs::weakly_canonical(path, ec).string();
    for (int s = 0; s < n && chosen < 0; ++s) {
      vtkStringArray* files = finder->GetFileNamesForSeries(s);
      for (vtkIdType i = 0; i < files->GetNumberOfValues(); ++i)
        if (fs::weakly_canonical(fs::path(std::string(files->GetValue(i))), ec).string() == wanted) chosen = s;
    }
    if (chosen < 0) throw InputError(path, "not a readable DICOM image file");
  } else {
    vtkIdType most = 0;
    for (int s = 0; s < n; ++s)
      if (finder->GetFileNamesForSeries(s)->GetNumberOfValues() > most) {
        most = finder->GetFileNamesForSeries(s)->GetNumberOfValues();
        chosen = s;
      }
    if (n > 1)
      notes.push_back(std::to_string(n) + " series in the directory; read the largest (" + std::to_string(most) +
                      " files); pass one of its files to choose another");
  }
  vtkStringArray* files = finder->GetFileNamesForSeries(chosen);
  std::vector<std::string> out;
  for (vtkIdType i = 0; i < files->GetNumberOfValues(); ++i) {
    out.push_back(files->GetValue(i));
    // An index may list files that are not there (a CD copied in part): named here, not by vtk-dicom's parser.
    if (folder.dicomdir && !fs::is_regular_file(out.back(), ec))
      throw InputError(out.back(), "listed in the folder's DICOMDIR but not there (a partly copied CD?)");
  }
  return out;
}

Vec3 crossOf(const double* r, const double* c) { return cross(Vec3{r[0], r[1], r[2]}, Vec3{c[0], c[1], c[2]}); }

// Files beside the series that are not part of it, e.g. "; IM-0004.dcm in the directory is not part of the
// series (unreadable, not an image, or another series)": a corrupt slice file is skipped by vtkDICOMDirectory
// and would otherwise show up only as a gap.
std::string outsiders(const std::vector<std::string>& files) {
  if (files.empty()) return "";
  std::error_code ec;
  std::vector<std::string> inSeries;
  for (const std::string& f : files) inSeries.push_back(fs::path(f).filename().string());
  std::vector<std::string> others;
  for (const auto& e : fs::directory_iterator(fs::path(files[0]).parent_path(), ec)) {
    const std::string name = e.path().filename().string();
    if (e.is_regular_file(ec) && std::find(inSeries.begin(), inSeries.end(), name) == inSeries.end()) others.push_back(name);
  }
  if (others.empty()) return "";
  std::sort(others.begin(), others.end());
  std::string list;
  for (std::size_t i = 0; i < others.size() && i < 3; ++i) list += (i ? ", " : "") + others[i];
  if (others.size() > 3) list += " and " + std::to_string(others.size() - 3) + " more";
  return "; " + list + (others.size() > 1 ? " in the directory are" : " in the directory is") +
         " not part of the series (unreadable, not an image, or another series)";
}

// The name of slice f's file, for messages ("?" when the series has more instances than files).
std::string sliceFileName(const std::vector<std::string>& files, int f) {
  return f < int(files.size()) ? fs::path(files[std::size_t(f)]).filename().string() : std::string("?");
}

// Within their plane, the slices of a gantry-tilted series are shifted in proportion to their distance along
// the normal (the reader's patient matrix, and the resampling, take the shift as one straight line from the
// first slice to the last); an untilted series is not shifted at all. A slice off that line means slices
// of different series, or positions that are simply wrong: stacking them would shear the volume unevenly.
// `positions`: each slice's ImagePositionPatient; `byPosition`: (distance along the normal, slice), sorted.
void checkInPlaneShifts(const std::string& path, vtkDICOMMetaData* meta, const Vec3& normal,
                        const std::vector<Vec3>& positions, const std::vector<std::pair<double, int>>& byPosition,
                        const std::vector<std::string>& files) {
  const auto position = [&](int f) { return positions[std::size_t(f)]; };
  const auto inPlane = [&](const Vec3& d) { return d - normal * dot(normal, d); };
  const vtkDICOMValue& pixel = meta->Get(0, DC::PixelSpacing);
  const double pixelMm = pixel.GetNumberOfValues() == 2 ? std::min(pixel.GetDouble(0), pixel.GetDouble(1)) : 0.0;
  const double tolerance = std::max(kInPlaneToleranceMm, std::isfinite(pixelMm) ? kInPlaneTolerancePixels * pixelMm : 0.0);
  const Vec3 first = position(byPosition.front().second);
  const double depth = byPosition.back().first - byPosition.front().first;
  if (!(depth > 0)) return;  // coincident slices: the spacing check names them
  const Vec3 shiftPerMm = inPlane(position(byPosition.back().second) - first) / depth;
  const double tiltDegrees = std::atan(norm(shiftPerMm)) * 180 / M_PI;
  if (tiltDegrees > kMaxTiltDegrees) {
    char m[200];
    std::snprintf(m, sizeof m, "the slices are shifted within their plane as by a gantry tilt of %.1f° (scanners tilt "
                  "at most about 30°): their positions are inconsistent", tiltDegrees);
    throw InputError(path, m);
  }
  for (const auto& [depthOf, f] : byPosition) {
    const double off = norm(inPlane(position(f) - first) - shiftPerMm * (depthOf - byPosition.front().first));
    if (off > tolerance) {
      char m[260];
      std::snprintf(m, sizeof m, "slice %s is %.3g mm off the line the other slices' positions follow within their "
                    "plane (slices of different series, or wrong positions)",
                    sliceFileName(files, f).c_str(), off);
      throw InputError(path, m);
    }
  }
}

// Orientation, size and spacing of single-frame slices must agree before they are stacked.
// `why`: what the messages add about files beside the series (outsiders, leftOut).
void checkSlices(const std::string& path, vtkDICOMMetaData* meta, const std::vector<std::string>& files,
                 const std::string& why) {
  const int n = meta->GetNumberOfInstances();
  if (n < 2) throw InputError(path, "the series has a single image; a CT volume needs at least 2 slices" + why);
  double iop0[6];
  const vtkDICOMValue& o0 = meta->Get(0, DC::ImageOrientationPatient);
  if (!o0.IsValid() || o0.GetNumberOfValues() != 6)
    throw InputError(files[0], "no ImageOrientationPatient: cannot place the slices in space");
  for (int k = 0; k < 6; ++k) iop0[k] = o0.GetDouble(std::size_t(k));
  const Vec3 normal = crossOf(iop0, iop0 + 3);
  const int rows0 = meta->Get(0, DC::Rows).AsInt(), cols0 = meta->Get(0, DC::Columns).AsInt();
  std::vector<std::pair<double, int>> pos;
  std::vector<Vec3> positions;
  for (int f = 0; f < n; ++f) {
    const std::string& file = f < int(files.size()) ? files[std::size_t(f)] : path;
    const vtkDICOMValue& o = meta->Get(f, DC::ImageOrientationPatient);
    const vtkDICOMValue& p = meta->Get(f, DC::ImagePositionPatient);
    if (!o.IsValid() || o.GetNumberOfValues() != 6 || !p.IsValid() || p.GetNumberOfValues() != 3)
      throw InputError(file, "no ImagePositionPatient/ImageOrientationPatient: cannot place the slice");
    for (int k = 0; k < 6; ++k)
      if (std::abs(o.GetDouble(std::size_t(k)) - iop0[k]) > 1e-3)
        throw InputError(file, "slice orientation differs from the rest of the series");
    if (meta->Get(f, DC::Rows).AsInt() != rows0 || meta->Get(f, DC::Columns).AsInt() != cols0)
      throw InputError(file, "slice size differs from the rest of the series");
    positions.push_back({p.GetDouble(0), p.GetDouble(1), p.GetDouble(2)});
    pos.emplace_back(dot(normal, positions.back()), f);
  }
  std::sort(pos.begin(), pos.end());
  checkInPlaneShifts(path, meta, normalized(normal), positions, pos, files);
  std::vector<double> gaps;
  for (std::size_t i = 1; i < pos.size(); ++i) gaps.push_back(pos[i].first - pos[i - 1].first);
  std::vector<double> sorted = gaps;
  std::nth_element(sorted.begin(), sorted.begin() + long(sorted.size() / 2), sorted.end());
  const double spacing = sorted[sorted.size() / 2];
  const auto fileOf = [&](std::size_t i) { return sliceFileName(files, pos[i].second); };
  for (std::size_t i = 0; i < gaps.size(); ++i) {
    if (gaps[i] < 1e-3)
      throw InputError(path, "slices " + fileOf(i) + " and " + fileOf(i + 1) + " are at the same position " +
                                 mm(pos[i].first) + " mm (duplicate slice or two series mixed?)");
    if (std::abs(gaps[i] - spacing) <= 0.01 * spacing + 1e-3) continue;
    const double ratio = gaps[i] / spacing;
    const long whole = std::lround(ratio);
    if (whole >= 2 && std::abs(ratio - double(whole)) < 0.05)
      throw InputError(path, "missing slice" + std::string(whole > 2 ? "s" : "") + ": gap of " + mm(gaps[i]) +
                                 " mm between " + fileOf(i) + " and " + fileOf(i + 1) + " where the spacing is " +
                                 mm(spacing) + " mm (" + std::to_string(whole - 1) + " slice" +
                                 (whole > 2 ? "s" : "") + " missing)" + why);
    throw InputError(path, "inconsistent slice spacing: " + mm(gaps[i]) + " mm between " + fileOf(i) + " and " +
                               fileOf(i + 1) + ", " + mm(spacing) + " mm elsewhere" + why);
  }
}

// The volume the headers declare, checked before vtk-dicom allocates it: Rows × Columns of 65535 in every
// slice asked for 64 GB (found while fuzzing, by editing every slice); uncompressed pixel data must also fit
// in the files.
void checkDeclaredSize(const std::string& path, vtkDICOMReader* reader, vtkDICOMMetaData* meta,
                       const std::vector<std::string>& files) {
  int ext[6] = {0, -1, 0, -1, 0, -1};
  reader->GetOutputInformation(0)->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), ext);
  std::uint64_t voxels = 1;
  std::string dims;
  for (int a = 0; a < 3; ++a) {
    const std::int64_t n = std::int64_t(ext[2 * a + 1]) - ext[2 * a] + 1;
    if (n < 1) throw InputError(path, "the series declares an empty image");
    voxels *= std::uint64_t(n);
    dims += (a ? "×" : "") + std::to_string(n);
  }
  if (voxels > kMaxVoxels)
    throw InputError(path, "the series declares " + dims + " voxels, more than the limit of 2^31 (wrong Rows, Columns or NumberOfFrames?)");
  const std::string syntax = meta->Get(0, DC::TransferSyntaxUID).AsString();
  const bool native = syntax == "1.2.840.10008.1.2" || syntax == "1.2.840.10008.1.2.1" || syntax == "1.2.840.10008.1.2.2";
  if (!native) return;  // compressed: the codec reports short data
  const std::uint64_t bits = voxels * std::uint64_t(std::max(1, meta->Get(0, DC::BitsAllocated).AsInt())) *
                             std::uint64_t(std::max(1, meta->Get(0, DC::SamplesPerPixel).AsInt()));
  const std::uint64_t bytes = (bits + 7) / 8;  // BitsAllocated 1 (bit-packed masks) included
  std::uint64_t held = 0;
  std::error_code ec;
  for (const std::string& f : files) held += fs::file_size(f, ec);
  if (bytes > held)
    throw InputError(path, "the series declares " + dims + " voxels (" + std::to_string(bytes) + " bytes of pixel data) but its " +
                               std::to_string(files.size()) + " file(s) hold " + std::to_string(held) +
                               " bytes (wrong Rows, Columns or NumberOfFrames?)");
}

}  // namespace

CtVolume readDicom(const std::string& path, const ReadTick& tick) {
  CtVolume v;
  v.sourcePath = path;
  v.format = "dicom";
  v.space = PatientSpace::LPS;
  FolderFiles folder;
  const std::vector<std::string> files = seriesFiles(path, v.notes, folder);

  VtkMessageCapture capture;
  auto reader = vtkSmartPointer<vtkDICOMReader>::New();
  capture.observe(reader);
  auto names = vtkSmartPointer<vtkStringArray>::New();
  for (const std::string& f : files) names->InsertNextValue(f);
  reader->SetFileNames(names);
  reader->SetMemoryRowOrderToFileNative();
  reader->AutoRescaleOn();
  reader->UpdateInformation();
  if (capture.anyError()) throw InputError(path, "cannot read the DICOM series: " + capture.firstMessage());
  vtkDICOMMetaData* meta = reader->GetMetaData();
  if (!meta) throw InputError(path, "cannot read the DICOM series meta data");
  const bool singleFrames = int(files.size()) == meta->GetNumberOfInstances() &&
                            meta->Get(0, DC::NumberOfFrames).AsInt() <= 1;
  if (singleFrames) checkSlices(path, meta, files, folder.broken.empty() ? outsiders(files) : leftOut(folder.broken));
  checkDeclaredSize(path, reader, meta, files);
  if (meta->Get(0, DC::Modality).AsString() == "CT") v.valueUnit = "HU";

  if (tick) capture.observeProgress(reader, tick);
  try {
    reader->Update();
    if (capture.cancelled()) throw ImportCancelled("reading");
  } catch (const std::bad_alloc&) {
    throw InputError(path, "out of memory reading the DICOM series");
  }
  if (capture.anyError()) throw InputError(path, "cannot read the DICOM pixel data: " + capture.firstMessage());
  vtkImageData* img = reader->GetOutput();
  vtkMatrix4x4* m = reader->GetPatientMatrix();
  if (!m) throw InputError(path, "the series gives no patient orientation");
  // A tilted gantry shifts each slice within its plane: the slice-to-slice step is not along the slices'
  // normal, so the voxels are sheared. vtk-dicom resamples such a series onto a rectangular grid.
  vtkSmartPointer<vtkDICOMCTRectifier> rectifier;
  if (const double tilt = vtkDICOMCTRectifier::GetGantryDetectorTilt(m); std::abs(tilt) > kTiltToRectifyDegrees) {
    rectifier = vtkSmartPointer<vtkDICOMCTRectifier>::New();
    capture.observe(rectifier);
    rectifier->SetInputConnection(reader->GetOutputPort());
    rectifier->SetVolumeMatrix(m);
    rectifier->SetInterpolationModeToLinear();  // no ringing beside bone for the threshold to pick up
    try {
      rectifier->Update();
    } catch (const std::bad_alloc&) {
      throw InputError(path, "out of memory resampling the gantry-tilted series");
    }
    if (capture.anyError()) throw InputError(path, "cannot resample the gantry-tilted series: " + capture.firstMessage());
    img = rectifier->GetOutput();
    m = rectifier->GetRectifiedMatrix();
    char note[160];
    std::snprintf(note, sizeof note, "gantry tilt of %.1f°: the sheared slices were resampled onto a rectangular grid "
                  "(linear interpolation)", tilt);
    v.notes.push_back(note);
  }
  vtkDataArray* scalars = img ? img->GetPointData()->GetScalars() : nullptr;
  if (!scalars || scalars->GetNumberOfComponents() != 1)
    throw InputError(path, "the series is not a single-component (grayscale) image");
  int ext[6];
  img->GetExtent(ext);
  for (int a = 0; a < 3; ++a) v.dims[std::size_t(a)] = ext[2 * a + 1] - ext[2 * a] + 1;
  if (std::size_t(scalars->GetNumberOfTuples()) != v.voxelCount())
    throw InputError(path, "the reader returned incomplete pixel data");
  v.values.resize(v.voxelCount());
  for (vtkIdType i = 0; i < scalars->GetNumberOfTuples(); ++i) v.values[std::size_t(i)] = float(scalars->GetComponent(i, 0));
  const int st = scalars->GetDataType();
  v.integerValued = st != VTK_FLOAT && st != VTK_DOUBLE;
  if (!v.integerValued) {
    v.integerValued = std::all_of(v.values.begin(), v.values.end(), [](float x) { return x == std::floor(x); });
  }

  double spacing[3], vtkOrigin[3];
  img->GetSpacing(spacing);
  img->GetOrigin(vtkOrigin);
  std::array<Vec3, 3> steps;
  for (int a = 0; a < 3; ++a) steps[std::size_t(a)] = Vec3{m->GetElement(0, a), m->GetElement(1, a), m->GetElement(2, a)} * spacing[a];
  setAxesFromSteps(v, steps, path, 0);
  for (int r = 0; r < 3; ++r) {
    double x = m->GetElement(r, 3);
    for (int c = 0; c < 3; ++c) x += m->GetElement(r, c) * vtkOrigin[c];
    v.origin[r] = x;
  }
  v.notes.push_back(std::to_string(files.size()) + " DICOM files, transfer syntax " +
                    meta->Get(0, DC::TransferSyntaxUID).AsString());
  return v;
}

}  // namespace reamsim::ct::io
