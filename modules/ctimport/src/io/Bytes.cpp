#include "Bytes.h"

#include <zlib.h>

#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "reamsim/mesh/MeshError.h"

namespace reamsim::ct::io {

std::size_t sampleSize(SampleType t) {
  switch (t) {
    case SampleType::Int8: case SampleType::UInt8: return 1;
    case SampleType::Int16: case SampleType::UInt16: return 2;
    case SampleType::Int32: case SampleType::UInt32: case SampleType::Float32: return 4;
    case SampleType::Int64: case SampleType::UInt64: case SampleType::Float64: return 8;
  }
  return 1;
}

bool isIntegerSample(SampleType t) { return t != SampleType::Float32 && t != SampleType::Float64; }

const char* toString(SampleType t) {
  switch (t) {
    case SampleType::Int8: return "int8";
    case SampleType::UInt8: return "uint8";
    case SampleType::Int16: return "int16";
    case SampleType::UInt16: return "uint16";
    case SampleType::Int32: return "int32";
    case SampleType::UInt32: return "uint32";
    case SampleType::Int64: return "int64";
    case SampleType::UInt64: return "uint64";
    case SampleType::Float32: return "float32";
    case SampleType::Float64: return "float64";
  }
  return "?";
}

std::uint64_t fileSize(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (ec || !fs::exists(st)) throw InputError(path, "file not found");
  if (fs::is_directory(st)) throw InputError(path, "is a directory, not a file");
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) throw InputError(path, "cannot read the file size: " + ec.message());
  return size;
}

std::string readWholeFile(const std::string& path) {
  const std::uint64_t size = fileSize(path);
  if (size > (std::uint64_t{4} << 30)) throw InputError(path, "file is larger than 4 GiB");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, std::string("cannot open: ") + std::strerror(errno));
  std::string bytes(static_cast<std::size_t>(size), '\0');
  if (size > 0 && !in.read(bytes.data(), static_cast<std::streamsize>(size)))
    throw InputError(path, "read error");
  return bytes;
}

std::string inflateExactly(const std::string& path, std::string_view compressed, std::size_t expectedBytes) {
  // The output grows as the stream really expands (doubling), so a header that lies about the size of
  // garbage data costs a few bytes, not the gigabytes it declares.
  std::string out(std::min<std::size_t>(expectedBytes, std::size_t{1} << 20), '\0');
  z_stream z{};
  if (inflateInit2(&z, 15 + 32) != Z_OK) throw InputError(path, "cannot initialise zlib");
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(compressed.data()));
  std::size_t inLeft = compressed.size(), produced = 0;
  int rc = Z_OK;
  // zlib counts in uInt: feed and drain in chunks so that > 4 GiB streams also work.
  const std::size_t chunk = std::size_t{1} << 30;
  while (rc != Z_STREAM_END) {
    if (z.avail_in == 0 && inLeft > 0) {
      z.avail_in = static_cast<uInt>(std::min(inLeft, chunk));
      inLeft -= z.avail_in;
    }
    char extra[1];
    if (produced == out.size() && out.size() < expectedBytes) out.resize(std::min(expectedBytes, 2 * out.size()));
    const bool full = produced == expectedBytes;
    z.next_out = reinterpret_cast<Bytef*>(full ? extra : out.data() + produced);
    z.avail_out = static_cast<uInt>(full ? 1 : std::min(out.size() - produced, chunk));
    const uInt before = z.avail_out;
    rc = inflate(&z, Z_NO_FLUSH);
    const std::size_t got = before - z.avail_out;
    if (full && got > 0) {
      inflateEnd(&z);
      throw InputError(path, "compressed data expands to more than the " + std::to_string(expectedBytes) +
                                 " bytes the header declares");
    }
    produced += got;
    if (rc == Z_STREAM_END) break;
    if (rc == Z_BUF_ERROR && z.avail_in == 0 && inLeft == 0) {
      inflateEnd(&z);
      throw InputError(path, "compressed data ends after " + std::to_string(produced) + " of " +
                                 std::to_string(expectedBytes) + " bytes (file truncated?)");
    }
    if (rc != Z_OK && rc != Z_BUF_ERROR) {
      const std::string msg = z.msg ? z.msg : "error " + std::to_string(rc);
      inflateEnd(&z);
      throw InputError(path, "corrupt compressed data: " + msg);
    }
  }
  inflateEnd(&z);
  if (produced != expectedBytes)
    throw InputError(path, "compressed data holds " + std::to_string(produced) + " bytes but the header declares " +
                               std::to_string(expectedBytes) + " (file truncated or wrong sizes?)");
  return out;
}

namespace {

template <class T>
void decodeTyped(const char* src, std::size_t count, bool bigEndian, float* dst) {
  for (std::size_t i = 0; i < count; ++i) dst[i] = static_cast<float>(loadScalar<T>(src + i * sizeof(T), bigEndian));
}

}  // namespace

void decodeSamples(const char* src, std::size_t count, SampleType type, bool bigEndian, float* dst) {
  switch (type) {
    case SampleType::Int8: decodeTyped<std::int8_t>(src, count, bigEndian, dst); break;
    case SampleType::UInt8: decodeTyped<std::uint8_t>(src, count, bigEndian, dst); break;
    case SampleType::Int16: decodeTyped<std::int16_t>(src, count, bigEndian, dst); break;
    case SampleType::UInt16: decodeTyped<std::uint16_t>(src, count, bigEndian, dst); break;
    case SampleType::Int32: decodeTyped<std::int32_t>(src, count, bigEndian, dst); break;
    case SampleType::UInt32: decodeTyped<std::uint32_t>(src, count, bigEndian, dst); break;
    case SampleType::Int64: decodeTyped<std::int64_t>(src, count, bigEndian, dst); break;
    case SampleType::UInt64: decodeTyped<std::uint64_t>(src, count, bigEndian, dst); break;
    case SampleType::Float32: decodeTyped<float>(src, count, bigEndian, dst); break;
    case SampleType::Float64: decodeTyped<double>(src, count, bigEndian, dst); break;
  }
}

void decodeAsciiSamples(const std::string& path, std::string_view text, std::size_t count, float* dst) {
  std::size_t pos = 0, n = 0;
  const auto isSep = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == ','; };
  while (true) {
    while (pos < text.size() && isSep(text[pos])) ++pos;
    if (pos >= text.size()) break;
    std::size_t end = pos;
    while (end < text.size() && !isSep(text[end])) ++end;
    if (n == count) throw InputError(path, "more than the " + std::to_string(count) + " values the header declares");
    double v = 0;
    const char* first = text.data() + pos;
    if (*first == '+') ++first;
    const auto r = std::from_chars(first, text.data() + end, v);
    if (r.ec != std::errc() || r.ptr != text.data() + end)
      throw InputError(path, "value " + std::to_string(n + 1) + " is not a number: '" +
                                 std::string(text.substr(pos, std::min<std::size_t>(end - pos, 40))) + "'");
    dst[n++] = static_cast<float>(v);
    pos = end;
  }
  if (n != count)
    throw InputError(path, "only " + std::to_string(n) + " of " + std::to_string(count) +
                               " values present (file truncated?)");
}

namespace {

// A NUL or other control byte would cut or garble a data file name in messages and in open() (found by
// fuzzing: "quarter.%d 1 9\0\0\0" was looked for as "quarter.%d 1 9"), and so would a name of 100k bytes.
void checkFileName(const std::string& headerPath, const std::string& name) {
  if (name.size() > 4096)  // PATH_MAX; a longer one would also drown the message that names it
    throw InputError(headerPath, "data file name of " + std::to_string(name.size()) + " bytes is too long");
  for (const char c : name)
    if (static_cast<unsigned char>(c) < 0x20)
      throw InputError(headerPath, "data file name contains a control character (byte " +
                                       std::to_string(int(static_cast<unsigned char>(c))) + ")");
}

}  // namespace

std::string formatNumbered(const std::string& path, const std::string& pattern, long value) {
  checkFileName(path, pattern);
  // Exactly one integer conversion, optionally with flags/width ("%d", "%03d", "%i"); "%%" is a literal.
  std::size_t conversions = 0;
  for (std::size_t i = 0; i < pattern.size(); ++i) {
    if (pattern[i] != '%') continue;
    if (i + 1 < pattern.size() && pattern[i + 1] == '%') { ++i; continue; }
    std::size_t j = i + 1;
    while (j < pattern.size() && std::strchr("0123456789-+ #", pattern[j])) ++j;
    if (j >= pattern.size() || (pattern[j] != 'd' && pattern[j] != 'i' && pattern[j] != 'u'))
      throw InputError(path, "data file pattern '" + pattern + "' must contain one %d-style number");
    ++conversions;
    i = j;
  }
  if (conversions != 1) throw InputError(path, "data file pattern '" + pattern + "' must contain exactly one %d");
  char buf[4096];
  std::string fmt = pattern;
  // Normalise the conversion to 'ld' so that the long argument is passed correctly.
  for (std::size_t i = 0; i < fmt.size(); ++i) {
    if (fmt[i] != '%') continue;
    if (i + 1 < fmt.size() && fmt[i + 1] == '%') { ++i; continue; }
    std::size_t j = i + 1;
    while (std::strchr("0123456789-+ #", fmt[j])) ++j;
    fmt.replace(j, 1, "ld");
    break;
  }
  const int n = std::snprintf(buf, sizeof buf, fmt.c_str(), value);
  if (n < 0 || std::size_t(n) >= sizeof buf) throw InputError(path, "data file name from '" + pattern + "' too long");
  return std::string(buf, std::size_t(n));
}

std::string besideHeader(const std::string& headerPath, const std::string& name) {
  namespace fs = std::filesystem;
  checkFileName(headerPath, name);
  const fs::path p(name);
  if (p.is_absolute()) return name;
  return (fs::path(headerPath).parent_path() / p).string();
}

}  // namespace reamsim::ct::io
