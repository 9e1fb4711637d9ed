#pragma once
// File access and raw sample decoding shared by the volume readers. Every failure is an InputError naming
// the file; nothing is allocated from a header's claims before they are checked against real sizes.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

namespace reamsim::ct::io {

enum class SampleType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Int64, UInt64, Float32, Float64 };

std::size_t sampleSize(SampleType t);
bool isIntegerSample(SampleType t);
const char* toString(SampleType t);

// Size of a regular file; throws if missing, a directory or unreadable.
std::uint64_t fileSize(const std::string& path);
// The whole file (≤ 4 GiB).
std::string readWholeFile(const std::string& path);

// Inflates a zlib or gzip stream (auto-detected) that must expand to exactly `expectedBytes`.
std::string inflateExactly(const std::string& path, std::string_view compressed, std::size_t expectedBytes);

// One value of type T at `p`, stored in the file's byte order (`bigEndian`).
template <class T>
T loadScalar(const void* p, bool bigEndian) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, p, sizeof(T));
  if (bigEndian != (__BYTE_ORDER__ == __ORDER_BIG_ENDIAN__)) std::reverse(b, b + sizeof(T));  // GCC/Clang macro
  T v;
  std::memcpy(&v, b, sizeof(T));
  return v;
}

// Converts `count` samples starting at `src` (file byte order given by `bigEndian`) to float.
void decodeSamples(const char* src, std::size_t count, SampleType type, bool bigEndian, float* dst);

// Whitespace-separated numbers (NRRD "ascii"/"text" encoding): exactly `count` of them.
void decodeAsciiSamples(const std::string& path, std::string_view text, std::size_t count, float* dst);

// printf-style file name pattern with one integer conversion (%d, %03d, %i ...), as in NRRD and MetaImage
// "data file: fmt min max step".
std::string formatNumbered(const std::string& path, const std::string& pattern, long value);

// Joins a data file name with the directory of the header file (absolute names are kept); a name with a
// control character or longer than 4096 bytes is an InputError naming the header.
std::string besideHeader(const std::string& headerPath, const std::string& name);

}  // namespace reamsim::ct::io
