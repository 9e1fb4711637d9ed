#include "FileBytes.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <system_error>

#include "Formats.h"
#include "reamsim/mesh/MeshError.h"

namespace reamsim::io {
namespace {

struct FileCloser {
  void operator()(std::FILE* f) const {
    if (f) std::fclose(f);
  }
};

}  // namespace

std::string errnoText(int err) { return err ? std::string(std::strerror(err)) : std::string("unknown error"); }

std::string readFileBytes(const std::string& path, const StageProgress* progress) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (ec || !fs::exists(st)) throw InputError(path, "file not found");
  if (fs::is_directory(st)) throw InputError(path, "is a directory, not a mesh file");
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) throw InputError(path, "cannot determine the file size: " + ec.message());
  if (size > kMaxMeshFileBytes)
    throw InputError(path, "file is too large (" + std::to_string(size) + " bytes; the limit is 2 GiB)");

  errno = 0;
  std::unique_ptr<std::FILE, FileCloser> f(std::fopen(path.c_str(), "rb"));
  if (!f) throw InputError(path, "cannot open the file for reading: " + errnoText(errno));
  std::string bytes(static_cast<std::size_t>(size), '\0');
  constexpr std::size_t kPiece = std::size_t{8} << 20;
  for (std::size_t done = 0; done < bytes.size();) {
    askReadGoesOn(progress, double(done) / double(bytes.size()));
    const std::size_t want = std::min(kPiece, bytes.size() - done);
    const std::size_t got = std::fread(bytes.data() + done, 1, want, f.get());
    if (got != want) throw InputError(path, "read error (file changed or unreadable while reading)");
    done += got;
  }
  if (bytes.empty()) throw InputError(path, "file is empty");
  return bytes;
}

void appendDouble(std::string& out, double value) {
  // printf's "%.17g" as in the "C" locale: snprintf would follow the C library's locale, which Qt sets from
  // the user's environment (a decimal comma in de_DE would end the number for every reader).
  char buf[40];
  const auto r = std::to_chars(buf, buf + sizeof buf, value, std::chars_format::general, 17);
  out.append(buf, r.ptr);
}

void appendTriple(std::string& out, double a, double b, double c) {
  appendDouble(out, a);
  out += ' ';
  appendDouble(out, b);
  out += ' ';
  appendDouble(out, c);
}

void appendVertexAndTriangleLines(std::string& out, const TriangleMesh& mesh) {
  for (const Vec3& p : mesh.vertices) {
    appendTriple(out, p.x, p.y, p.z);
    out += '\n';
  }
  for (const Triangle& t : mesh.triangles)
    out += "3 " + std::to_string(t[0]) + ' ' + std::to_string(t[1]) + ' ' + std::to_string(t[2]) + '\n';
}

}  // namespace reamsim::io
