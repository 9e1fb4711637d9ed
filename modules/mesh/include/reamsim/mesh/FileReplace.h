#pragma once
// Writing a file so that a failure never costs the user the file that was there.
#include <string>

#include "reamsim/mesh/RepairProgress.h"

namespace reamsim {

// Thrown when a write's progress callback asked to stop: the file that was there is unchanged.
class WriteCancelled : public StageCancelled {
 public:
  explicit WriteCancelled(const std::string& stage)
      : StageCancelled("writing cancelled during " + stage + " (the file there is unchanged)", stage) {}
};

// Replaces `path` with `bytes` all at once: the bytes go to a new file beside it, are flushed to the disk,
// and only then is that file renamed over `path` (a rename within a directory is atomic). A failure at any
// point (disk full, no permission, a size limit, a missing folder) leaves whatever was at `path` as it was,
// removes the new file and throws InputError naming `path` and the reason. An existing file keeps its mode
// and, where allowed, its owner (root only), group, ACL and user.* attributes; a symbolic link keeps
// pointing where it did (its target is replaced, or created when it dangles). A file with other names (hard
// links) is overwritten in place once the new file beside it is complete and flushed, so every name sees the
// new content: the one case where a failure (during that overwrite) can leave the file part old, part new;
// then the complete new content is kept as `path`.reamsim-saved and the error names it. A linked file that
// cannot be opened for writing is replaced by the rename (its other names keep the old content). A device or pipe (/dev/stdout),
// and a file in a folder where no new file can be made, are written in place, as a plain write would.
// New files an earlier process left beside `path` when it died before renaming are removed (when over an hour
// old and their process is gone).
// `progress`, when given, hears the fraction written ("writing", in pieces of 8 MiB) and "flushing"; returning
// false stops before anything is replaced (the new file is removed) with WriteCancelled. A device or a file
// written in place is asked once, before it is opened.
void replaceFile(const std::string& path, const std::string& bytes, const ProgressCallback& progress = {});

// Gives the file at `to` the owner, group, mode, ACLs and user attributes of the file at `from`, as far as this
// process may (best effort, as replaceFile does for the file it replaces): for a file written beside another
// by other means (a bone's undo history beside the bone). Nothing happens when either cannot be opened.
void keepFileAttributes(const std::string& from, const std::string& to);

}  // namespace reamsim
