#pragma once
// The voxel data of a header-based format (NRRD, MetaImage): one or more parts (the header file itself
// after its header, one external file, or one file per slice block), raw, zlib/gzip or ASCII encoded.
// Every part's size is checked against what it must hold; messages name the part's file.
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "Bytes.h"

namespace reamsim::ct::io {

enum class Encoding { Raw, Deflate, Ascii };  // Deflate: zlib or gzip stream

struct PayloadPart {
  std::string path;              // file holding this part
  std::string_view inMemory;     // if non-empty: the part's bytes are these (attached data), `path` names them
  std::uint64_t byteSkip = 0;    // bytes to skip (after lineSkip); raw: before the data, deflate: after inflating
  bool dataAtEnd = false;        // raw only: the data are the last bytes of the file (NRRD "byte skip: -1")
  long lineSkip = 0;             // text lines to skip first (NRRD "line skip")
  std::size_t samples = 0;       // samples this part holds
  std::uint64_t compressedBytes = 0;  // deflate: bytes of compressed data if known (MetaImage), 0 = all
  bool oneOfMany = false;        // one of several slice files (a missing one is a missing slice)
};

struct PayloadSpec {
  std::string header;  // the header file that names the data files (for messages about them)
  SampleType type = SampleType::Int16;
  bool bigEndian = false;
  Encoding encoding = Encoding::Raw;
  std::vector<PayloadPart> parts;
};

// Checks, from file sizes alone, that every part can hold its samples (raw: exactly enough bytes after the
// skips; compressed: no more than zlib's maximum ratio; ascii: two bytes per value) — before anything is
// allocated from the header's sizes. Throws InputError naming the part's file.
void checkPayloadSizes(const PayloadSpec& spec);

// Decodes all parts in order into `out`, sized here to the sum of the parts' samples only once the first
// part's data has been read (a compressed part inflated and checked), so that a lying header over garbage
// data allocates nothing. Notes (extra bytes ignored) are appended to `notes`.
// `tick(fraction)` is called after each part; returning false throws ImportCancelled.
void readPayload(const PayloadSpec& spec, std::vector<float>& out, std::vector<std::string>& notes,
                 const std::function<bool(double)>& tick = {});

}  // namespace reamsim::ct::io
