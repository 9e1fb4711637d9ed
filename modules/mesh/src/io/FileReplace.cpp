// replaceFile (reamsim/mesh/FileReplace.h): write beside, flush, rename over. Writing the file in place
// truncated it first, so a save that failed half way (disk full) destroyed the copy the user had.
#include "reamsim/mesh/FileReplace.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/xattr.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <filesystem>
#include <string>

#include "FileBytes.h"
#include "reamsim/mesh/MeshError.h"

namespace reamsim {
namespace {

namespace fs = std::filesystem;
using io::errnoText;

// The file a path names through any symbolic links, the last of which may dangle (its target is created).
fs::path throughLinks(fs::path p) {
  std::error_code ec;
  for (int hops = 0; hops < 40 && fs::is_symlink(fs::symlink_status(p, ec)); ++hops) {
    const fs::path to = fs::read_symlink(p, ec);
    if (ec) break;
    p = to.is_absolute() ? to : p.parent_path() / to;
  }
  return p;
}

// Asks `progress` (when there is one) whether to go on; throws WriteCancelled if not.
void check(const ProgressCallback& progress, double fraction, const std::string& stage) {
  if (progress && !progress(fraction, stage)) throw WriteCancelled(stage);
}

// Writes all of `bytes` to `fd`, asking `progress` between pieces; false with errno set on failure.
bool writeAll(int fd, const std::string& bytes, const ProgressCallback& progress = {}) {
  constexpr std::size_t kPiece = std::size_t(8) << 20;  // a cancel is heard within one piece (~10-50 ms)
  for (std::size_t done = 0; done < bytes.size();) {
    if (progress) check(progress, double(done) / double(bytes.size()), "writing");
    const std::size_t want = progress ? std::min(kPiece, bytes.size() - done) : bytes.size() - done;
    const ssize_t n = ::write(fd, bytes.data() + done, want);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      if (n == 0) errno = ENOSPC;
      return false;
    }
    done += static_cast<std::size_t>(n);
  }
  return true;
}

// A device, a pipe or a file in a folder where no new file can be made: written where it is, as before
// (there is nothing to rename over a device, and no room beside the file).
void writeInPlace(const std::string& path, const fs::path& target, const std::string& bytes) {
  const int fd = ::open(target.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
  if (fd < 0) throw InputError(path, "cannot open the file for writing: " + errnoText(errno));
  const bool ok = writeAll(fd, bytes);
  const int err = errno;
  if (::close(fd) != 0 && ok) throw InputError(path, "write error on close: " + errnoText(errno));
  if (!ok) throw InputError(path, "write error: " + errnoText(err));
}

// Closes the descriptor and removes the new file unless it was renamed into place.
class NewFile {
 public:
  NewFile(std::string path, int fd) : path_(std::move(path)), fd_(fd) {}
  NewFile(const NewFile&) = delete;
  NewFile& operator=(const NewFile&) = delete;
  ~NewFile() {
    if (fd_ >= 0) ::close(fd_);
    if (!placed_) ::unlink(path_.c_str());
  }
  int fd() const { return fd_; }
  int close() {
    const int r = ::close(fd_);
    fd_ = -1;
    return r;
  }
  void placed() { placed_ = true; }

 private:
  std::string path_;
  int fd_;
  bool placed_ = false;
};

// The replaced file's ACL (system.posix_acl_access) and the user's own attributes (user.*) on the new file.
// Nothing else: security.* and trusted.* describe the old content (an IMA signature would not match the new
// one). Best effort, as the mode: a file system without them is skipped.
void copyAclAndUserAttributes(const fs::path& from, int toFd) {
  const ssize_t size = ::listxattr(from.c_str(), nullptr, 0);
  if (size <= 0) return;
  std::string names(static_cast<std::size_t>(size), '\0');
  const ssize_t got = ::listxattr(from.c_str(), names.data(), names.size());
  if (got <= 0) return;
  names.resize(static_cast<std::size_t>(got));
  std::string value;
  for (std::size_t at = 0; at < names.size();) {
    const std::string name(names.c_str() + at);
    at += name.size() + 1;
    if (name != "system.posix_acl_access" && name.compare(0, 5, "user.") != 0) continue;
    const ssize_t n = ::getxattr(from.c_str(), name.c_str(), nullptr, 0);
    if (n < 0) continue;
    value.resize(static_cast<std::size_t>(n));
    if (n > 0 && ::getxattr(from.c_str(), name.c_str(), value.data(), value.size()) != n) continue;
    (void)::fsetxattr(toFd, name.c_str(), value.data(), value.size(), 0);
  }
}

// New files an earlier process left beside `target` (".NAME.reamsim-PID-STAMP-COUNT.part") when it died between
// writing and renaming: removed when that process is gone and the file is over an hour old. The age keeps a
// writer on another machine (a shared folder) or in another PID namespace, whose PID means nothing here, safe:
// no save takes an hour. Names not exactly in this pattern are left alone.
void removeLeftNewFiles(const fs::path& dir, const fs::path& target) {
  const std::string prefix = "." + target.filename().string() + ".reamsim-", suffix = ".part";
  const auto digitsAt = [](const std::string& s, std::size_t from, std::size_t to) {
    return to > from && s.find_first_not_of("0123456789", from) >= to;
  };
  const auto oldEnough = fs::file_time_type::clock::now() - std::chrono::hours(1);
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() <= prefix.size() + suffix.size() || name.compare(0, prefix.size(), prefix) != 0 ||
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
      continue;
    const std::size_t body = prefix.size(), bodyEnd = name.size() - suffix.size();
    const std::size_t dash1 = name.find('-', body), dash2 = dash1 == std::string::npos ? dash1 : name.find('-', dash1 + 1);
    if (dash2 == std::string::npos || dash2 >= bodyEnd || !digitsAt(name, body, dash1) ||
        !digitsAt(name, dash1 + 1, dash2) || !digitsAt(name, dash2 + 1, bodyEnd) || dash1 - body > 9)
      continue;
    const pid_t pid = static_cast<pid_t>(std::stol(name.substr(body, dash1 - body)));
    if (pid <= 0 || pid == ::getpid()) continue;
    std::error_code timeError;
    const auto written = fs::last_write_time(it->path(), timeError);
    if (timeError || written > oldEnough) continue;
    if (::kill(pid, 0) != 0 && errno == ESRCH) ::unlink(it->path().c_str());
  }
}

// The replaced file's owner and group on the new file. Only a privileged process may give a file away
// (root saving a user's mesh); otherwise the group alone, where the user belongs to it.
void keepOwnerAndGroup(int fd, const struct stat& old) {
  if (old.st_uid == ::geteuid() && old.st_gid == ::getegid()) return;
  if (old.st_uid != ::geteuid() && ::fchown(fd, old.st_uid, old.st_gid) == 0) return;
  if (old.st_gid != ::getegid()) (void)::fchown(fd, static_cast<uid_t>(-1), old.st_gid);
}

// A file with other names (hard links): a rename would give this name a new file and leave the others with
// the old content, so the file itself is overwritten, as a plain write would, but only once the complete new
// content is safe on the disk beside it. If the overwrite fails half way, that copy is kept under a name the
// clean-up of left files never touches (NAME.reamsim-saved[-N]) and the error says where it is; otherwise it
// is removed. False when the file cannot be opened for writing (read-only) or is no longer the file that was
// stat'ed (replaced meanwhile, e.g. by a symbolic link): then it is replaced by the rename, as a file without
// other names (they keep the old content).
bool overwriteLinkedFile(const std::string& path, const fs::path& target, const struct stat& old,
                         const std::string& bytes, NewFile& copy, const std::string& copyPath) {
  // O_NONBLOCK: a pipe put there meanwhile must not block the open (it fails the same-file check below).
  const int fd = ::open(target.c_str(), O_WRONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return false;
  struct stat now {};
  if (::fstat(fd, &now) != 0 || now.st_dev != old.st_dev || now.st_ino != old.st_ino || !S_ISREG(now.st_mode)) {
    ::close(fd);
    return false;
  }
  bool ok = writeAll(fd, bytes) && ::ftruncate(fd, static_cast<off_t>(bytes.size())) == 0 && ::fsync(fd) == 0;
  int err = errno;
  if (::close(fd) != 0 && ok) {
    ok = false;
    err = errno;
  }
  if (ok) return true;
  // The file there may now be part old, part new: keep the complete new content where the user can find it.
  copy.placed();
  std::string kept = copyPath;
  for (int n = 0; n < 100; ++n) {
    const std::string name = target.string() + ".reamsim-saved" + (n ? "-" + std::to_string(n) : std::string());
    if (::link(copyPath.c_str(), name.c_str()) == 0) {  // link + unlink: never over an existing file
      ::unlink(copyPath.c_str());
      kept = name;
      break;
    }
    if (errno != EEXIST) break;
  }
  throw InputError(path, "write error: " + errnoText(err) + " (the file has other names and was written in place; "
                                                            "the complete new content is in " + kept + ")");
}

}  // namespace

void keepFileAttributes(const std::string& from, const std::string& to) {
  struct stat old {};
  if (::stat(from.c_str(), &old) != 0) return;
  const int fd = ::open(to.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return;
  keepOwnerAndGroup(fd, old);
  (void)::fchmod(fd, old.st_mode & 07777);  // after the group: a chown may clear set-id bits
  copyAclAndUserAttributes(throughLinks(from), fd);
  ::close(fd);
}

void replaceFile(const std::string& path, const std::string& bytes, const ProgressCallback& progress) {
  const fs::path target = throughLinks(fs::path(path));
  struct stat old {};
  const bool existed = ::stat(target.c_str(), &old) == 0;
  if (existed && S_ISDIR(old.st_mode)) throw InputError(path, "cannot write: it is a folder");
  if (existed && !S_ISREG(old.st_mode)) {
    check(progress, 0, "writing");
    return writeInPlace(path, target, bytes);
  }

  // A new name beside the target: 0666 less the umask, as a file the program created directly. A name
  // left by an earlier process (a crash between writing and renaming) is skipped, not reused.
  static std::atomic<unsigned> counter{0};
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  const auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
  std::string temp;
  int fd = -1;
  for (int attempt = 0; attempt < 100 && fd < 0; ++attempt) {
    temp = (dir / ("." + target.filename().string() + ".reamsim-" + std::to_string(::getpid()) + "-" +
                   std::to_string(stamp) + "-" + std::to_string(counter.fetch_add(1)) + ".part"))
               .string();
    fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0 && errno != EEXIST) break;
  }
  if (fd < 0) {
    const int err = errno;
    // No new file can be made in the folder, but the file there may be written: as before.
    if (existed && (err == EACCES || err == EPERM || err == EROFS)) {
      check(progress, 0, "writing");
      return writeInPlace(path, target, bytes);
    }
    throw InputError(path, "cannot create a file in " + dir.string() + ": " + errnoText(err));
  }
  NewFile file(temp, fd);
  removeLeftNewFiles(dir, target);
  if (existed) {  // the replaced file's owner, group, mode and ACLs (best effort, as far as we may)
    keepOwnerAndGroup(fd, old);
    (void)::fchmod(fd, old.st_mode & 07777);  // after the group: a chown may clear set-id bits
    copyAclAndUserAttributes(target, fd);     // after the mode: an ACL's mask and the mode are one
  }
  const auto failed = [&](const std::string& what) {
    const int err = errno;
    return InputError(path, what + ": " + errnoText(err) + " (the file there is unchanged)");
  };
  if (!writeAll(fd, bytes, progress)) throw failed("write error");
  check(progress, 1, "flushing");
  if (::fsync(fd) != 0) throw failed("write error while flushing");
  if (file.close() != 0) throw failed("write error on close");
  check(progress, 1, "flushing");  // the last moment a cancel can keep the old file
  if (existed && old.st_nlink > 1 && overwriteLinkedFile(path, target, old, bytes, file, temp)) return;
  if (::rename(temp.c_str(), target.c_str()) != 0) throw failed("cannot replace the file");
  file.placed();
  // The rename itself on the disk (best effort: some file systems refuse to sync a folder).
  const int dirFd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dirFd >= 0) {
    (void)::fsync(dirFd);
    ::close(dirFd);
  }
}

}  // namespace reamsim
