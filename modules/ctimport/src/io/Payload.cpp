#include "Payload.h"

#include <filesystem>

#include "reamsim/ctimport/Progress.h"
#include "reamsim/mesh/MeshError.h"

namespace reamsim::ct::io {
namespace {

std::size_t skipLines(const std::string& path, std::string_view bytes, long lines) {
  std::size_t pos = 0;
  for (long i = 0; i < lines; ++i) {
    const std::size_t nl = bytes.find('\n', pos);
    if (nl == std::string_view::npos) throw InputError(path, "fewer than " + std::to_string(lines) + " lines to skip");
    pos = nl + 1;
  }
  return pos;
}

// "data file named by v.mhd: file not found (missing slice file?)": the header is named too, since a typo in it
// is the likelier cause.
std::string dataFileProblem(const PayloadSpec& spec, const PayloadPart& part, const std::string& problem) {
  const std::string by = spec.header.empty() ? "" : " named by " + std::filesystem::path(spec.header).filename().string();
  return "data file" + by + ": " + problem + (part.oneOfMany ? " (missing slice file?)" : "");
}

// Runs `step` on a part; a problem with a detached data file also names the header that named it.
template <typename Step>
void namingHeader(const PayloadSpec& spec, const PayloadPart& part, Step step) {
  try {
    step();
  } catch (const InputError& e) {
    if (spec.header.empty() || part.path == spec.header || e.file() != part.path ||
        e.problem().find(" named by ") != std::string::npos)
      throw;
    throw InputError(e.file(), e.line(), e.problem() + " (data file named by " +
                                             std::filesystem::path(spec.header).filename().string() + ")");
  }
}

// `out()`: where the part's samples go, called once its data are read and checked.
void readPart(const PayloadSpec& spec, const PayloadPart& part, const std::function<float*()>& out,
              std::vector<std::string>& notes) {
  std::string owned;
  std::string_view bytes = part.inMemory;
  if (bytes.empty()) {
    try {
      owned = readWholeFile(part.path);
    } catch (const InputError& e) {
      throw InputError(part.path, dataFileProblem(spec, part, e.problem()));
    }
    bytes = owned;
  }
  const std::size_t start = skipLines(part.path, bytes, part.lineSkip);
  bytes.remove_prefix(start);
  const std::size_t sampleBytes = sampleSize(spec.type);
  const std::uint64_t needed = std::uint64_t(part.samples) * sampleBytes;

  if (spec.encoding == Encoding::Raw) {
    std::uint64_t skip = part.byteSkip;
    if (part.dataAtEnd) {
      if (bytes.size() < needed)
        throw InputError(part.path, "holds " + std::to_string(bytes.size()) + " bytes of data, " +
                                        std::to_string(needed) + " expected (file truncated?)");
      skip = bytes.size() - needed;
    }
    if (skip > bytes.size() || bytes.size() - skip < needed)
      throw InputError(part.path, "holds " + std::to_string(bytes.size() > skip ? bytes.size() - skip : 0) +
                                      " bytes of voxel data, " + std::to_string(needed) + " expected for " +
                                      std::to_string(part.samples) + " " + toString(spec.type) +
                                      " samples (file truncated or wrong sizes in the header?)");
    if (bytes.size() - skip > needed && !part.dataAtEnd)
      notes.push_back(part.path + ": " + std::to_string(bytes.size() - skip - needed) +
                      " bytes after the voxel data were ignored");
    decodeSamples(bytes.data() + skip, part.samples, spec.type, spec.bigEndian, out());
    return;
  }
  if (spec.encoding == Encoding::Ascii) {
    if (part.byteSkip > bytes.size()) throw InputError(part.path, "byte skip beyond the end of the file");
    bytes.remove_prefix(static_cast<std::size_t>(part.byteSkip));
    decodeAsciiSamples(part.path, bytes, part.samples, out());
    return;
  }
  // Deflate.
  std::string_view compressed = bytes;
  if (part.compressedBytes > 0) {
    if (part.compressedBytes > bytes.size())
      throw InputError(part.path, "header declares " + std::to_string(part.compressedBytes) +
                                      " bytes of compressed data but only " + std::to_string(bytes.size()) +
                                      " follow (file truncated?)");
    compressed = bytes.substr(0, static_cast<std::size_t>(part.compressedBytes));
  }
  // A compressed stream cannot expand by more than ~1032:1; refuse lying sizes before allocating.
  if (needed + part.byteSkip > std::uint64_t(compressed.size()) * 1100 + 4096)
    throw InputError(part.path, "header declares " + std::to_string(needed) + " bytes of voxel data but only " +
                                    std::to_string(compressed.size()) +
                                    " compressed bytes are present (file truncated or wrong sizes?)");
  const std::string raw = inflateExactly(part.path, compressed, static_cast<std::size_t>(needed + part.byteSkip));
  decodeSamples(raw.data() + part.byteSkip, part.samples, spec.type, spec.bigEndian, out());
}

}  // namespace

void checkPayloadSizes(const PayloadSpec& spec) {
  for (const PayloadPart& part : spec.parts) namingHeader(spec, part, [&] {
    std::uint64_t available = part.inMemory.size();
    if (part.inMemory.empty()) {
      try {
        available = fileSize(part.path);
      } catch (const InputError& e) {
        throw InputError(part.path, dataFileProblem(spec, part, e.problem()));
      }
    }
    const std::uint64_t needed = std::uint64_t(part.samples) * sampleSize(spec.type);
    const std::uint64_t skip = part.dataAtEnd ? 0 : part.byteSkip;
    bool ok = true;
    if (spec.encoding == Encoding::Raw) ok = available >= needed + skip;
    else if (spec.encoding == Encoding::Deflate) ok = needed <= available * 1100 + 4096;
    else ok = available >= 2 * std::uint64_t(part.samples) - 1;
    if (!ok)
      throw InputError(part.path, "holds " + std::to_string(available) + " bytes, too few for the " +
                                      std::to_string(part.samples) + " " + toString(spec.type) +
                                      " samples expected for it (file truncated or wrong sizes in the header?)");
  });
}

void readPayload(const PayloadSpec& spec, std::vector<float>& out, std::vector<std::string>& notes,
                 const std::function<bool(double)>& tick) {
  std::size_t total = 0;
  for (const PayloadPart& part : spec.parts) total += part.samples;
  std::size_t offset = 0;
  for (std::size_t i = 0; i < spec.parts.size(); ++i) {
    namingHeader(spec, spec.parts[i], [&] {
      readPart(spec, spec.parts[i], [&]() -> float* {
        if (out.size() != total) out.assign(total, 0.0f);
        return out.data() + offset;
      }, notes);
    });
    offset += spec.parts[i].samples;
    if (tick && !tick(0.95 * double(i + 1) / double(spec.parts.size()))) throw ImportCancelled("reading");
  }
}

}  // namespace reamsim::ct::io
