// replaceFile (reamsim/mesh/FileReplace.h): write beside, flush, rename over. Writing the file in place
// truncated it first, so a save that failed half way (disk full) destroyed the copy the user had.
#include "reamsim/mesh/FileReplace.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include "reamsim/mesh/MeshError.h"

namespace reamsim {
namespace {

namespace fs = std::filesystem;

std::string errnoText(int err) { return err ? std::string(std::strerror(err)) : std::string("unknown error"); }

// Closes the descriptor and removes the new file unless it was renamed into place.
class NewFile {
 public:
  NewFile(std::string path, int fd) : path_(std::move(path)), fd_(fd) {}
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

}  // namespace

void replaceFile(const std::string& path, const std::string& bytes) {
  std::error_code ec;
  fs::path target(path);
  // Through a symbolic link to the file it names, so that the link stays a link.
  if (fs::is_symlink(fs::symlink_status(target, ec))) {
    const fs::path resolved = fs::weakly_canonical(target, ec);
    if (!ec) target = resolved;
  }
  const fs::file_status st = fs::status(target, ec);
  if (fs::is_directory(st)) throw InputError(path, "cannot write: it is a folder");
  const bool existed = fs::exists(st);

  static std::atomic<unsigned> counter{0};
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  const std::string temp =
      (dir / ("." + target.filename().string() + ".reamsim-" + std::to_string(::getpid()) + "-" +
              std::to_string(counter.fetch_add(1)) + ".part"))
          .string();
  // 0666 less the umask, as a file the program created directly; an existing file's own mode below.
  const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0) throw InputError(path, "cannot open the file for writing: " + errnoText(errno));
  NewFile file(temp, fd);
  if (existed) {
    struct stat old {};
    if (::stat(target.c_str(), &old) == 0) (void)::fchmod(fd, old.st_mode & 07777);
  }
  for (std::size_t done = 0; done < bytes.size();) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw InputError(path, "write error: " + errnoText(n < 0 ? errno : ENOSPC) + " (the file there is unchanged)");
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) throw InputError(path, "write error while flushing: " + errnoText(errno) + " (the file there is unchanged)");
  if (file.close() != 0) throw InputError(path, "write error on close: " + errnoText(errno) + " (the file there is unchanged)");
  if (::rename(temp.c_str(), target.c_str()) != 0)
    throw InputError(path, "cannot replace the file: " + errnoText(errno) + " (the file there is unchanged)");
  file.placed();
  // The rename itself on the disk (best effort: some file systems refuse to sync a folder).
  const int dirFd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dirFd >= 0) {
    (void)::fsync(dirFd);
    ::close(dirFd);
  }
}

}  // namespace reamsim
