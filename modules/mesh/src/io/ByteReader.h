#pragma once
// Bounds-checked reader of little/big-endian binary data in memory. Every read checks the remaining size
// first, so a truncated or lying file ends in an InputError instead of an out-of-bounds read.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

#include "reamsim/mesh/MeshError.h"

namespace reamsim::io {

class ByteReader {
 public:
  ByteReader(std::string_view data, std::string file, bool bigEndian)
      : data_(data), file_(std::move(file)), bigEndian_(bigEndian) {}

  std::size_t offset() const { return pos_; }
  std::size_t remaining() const { return data_.size() - pos_; }

  // Throws unless n more bytes exist; `what` says what was being read, for the message.
  void need(std::size_t n, const std::string& what) const {
    if (n > remaining())
      throw InputError(file_, "unexpected end of data while reading " + what + " at byte " + std::to_string(pos_) +
                                  " (file truncated?)");
  }
  void skip(std::size_t n, const std::string& what) {
    need(n, what);
    pos_ += n;
  }

  template <class T>
  T read(const std::string& what) {
    need(sizeof(T), what);
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, data_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    if (bigEndian_ != hostIsBigEndian())
      for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
    T value;
    std::memcpy(&value, bytes, sizeof(T));
    return value;
  }

  const std::string& file() const { return file_; }

  static bool hostIsBigEndian() {
    const std::uint16_t probe = 1;
    unsigned char first;
    std::memcpy(&first, &probe, 1);
    return first == 0;
  }

 private:
  std::string_view data_;
  std::string file_;
  bool bigEndian_;
  std::size_t pos_ = 0;
};

// Appends the little-endian bytes of a trivially copyable value (used by binary writers).
template <class T>
void appendLittleEndian(std::string& out, T value) {
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if (ByteReader::hostIsBigEndian())
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
  out.append(reinterpret_cast<const char*>(bytes), sizeof(T));
}

}  // namespace reamsim::io
