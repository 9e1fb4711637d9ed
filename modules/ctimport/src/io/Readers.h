#pragma once
// One reader per format; readVolume (VolumeIO.cpp) picks one and checks the result.
#include <functional>
#include <string>

#include "reamsim/ctimport/CtVolume.h"

namespace reamsim::ct::io {

// Reports the fraction read; returns false if the user cancelled (the reader then throws ImportCancelled).
using ReadTick = std::function<bool(double)>;

CtVolume readNrrd(const std::string& path, const ReadTick& tick);
CtVolume readMetaImage(const std::string& path, const ReadTick& tick);
CtVolume readNifti(const std::string& path, const ReadTick& tick);
CtVolume readDicom(const std::string& path, const ReadTick& tick);  // a directory, or one file of the series

}  // namespace reamsim::ct::io
