#pragma once
// Writing a file so that a failure never costs the user the file that was there.
#include <string>

namespace reamsim {

// Replaces `path` with `bytes` all at once: the bytes go to a new file beside it, are flushed to the disk,
// and only then is that file renamed over `path` (a rename within a directory is atomic). A failure at any
// point (disk full, no permission, a size limit, a missing folder) leaves whatever was at `path` as it was,
// removes the new file and throws InputError naming `path` and the reason. An existing file keeps its
// permissions; a symbolic link keeps pointing where it did (its target is replaced).
void replaceFile(const std::string& path, const std::string& bytes);

}  // namespace reamsim
