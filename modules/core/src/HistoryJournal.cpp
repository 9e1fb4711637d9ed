#include "reamsim/core/HistoryJournal.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <optional>
#include <unordered_map>
#include <cerrno>
#include <fcntl.h>
#include <filesystem>
#include <unistd.h>

#include "reamsim/mesh/MeshError.h"

namespace reamsim {
namespace {

// File: kMagic, then records. Record: kRecordMagic (u32), payload size (u64), payload, FNV-1a 64 of the
// payload (u64). Payload: revision, parent revision (0: the first state) (u64 each), the state's live triangle
// and vertex counts (u64 each, checked after the replay), its volume origin (3 × f64: the first state's is
// taken, see BoneState::fromMesh), label (u32 size, bytes), removed triangle slots (u32 count, u32 each), new vertices (u32 count; u32 slot, 3 × f64 each), added
// triangles (u32 count; u32 slot, 3 × u32 corner slots each). Little-endian, as the machine that wrote it
// (a recovery copy is read back where it was written).
constexpr char kMagic[8] = {'R', 'S', 'H', 'J', 'R', 'N', 'L', '1'};
constexpr std::uint32_t kRecordMagic = 0x44434552u;  // "RECD"
constexpr std::size_t kRecordOverhead = 4 + 8 + 8;
constexpr std::uint32_t kMaxLabel = 4096;
constexpr std::uint32_t kBad = BoneState::kBadSlot;

std::uint64_t fnv1a(const char* data, std::size_t size) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (std::size_t i = 0; i < size; ++i) {
    h ^= static_cast<unsigned char>(data[i]);
    h *= 0x100000001b3ull;
  }
  return h;
}

template <class T>
void put(std::string& out, const T& v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof v);
}

// Reads a payload; every read is bounds-checked, and a short one is the record's fault.
class PayloadReader {
 public:
  PayloadReader(const std::string& file, const char* data, std::size_t size) : file_(file), p_(data), end_(data + size) {}
  template <class T>
  T get() {
    if (std::size_t(end_ - p_) < sizeof(T)) throw InputError(file_, "a record ends inside its data");
    T v;
    std::memcpy(&v, p_, sizeof v);
    p_ += sizeof v;
    return v;
  }
  std::string bytes(std::size_t n) {
    if (std::size_t(end_ - p_) < n) throw InputError(file_, "a record ends inside its data");
    std::string s(p_, n);
    p_ += n;
    return s;
  }
  // A count of items of `itemBytes` each that the rest of the payload can hold.
  std::uint32_t count(std::size_t itemBytes) {
    const std::uint32_t n = get<std::uint32_t>();
    if (n > std::size_t(end_ - p_) / itemBytes) throw InputError(file_, "a record's count exceeds its data");
    return n;
  }
  bool done() const { return p_ == end_; }

 private:
  const std::string& file_;
  const char* p_;
  const char* end_;
};

struct Record {
  std::uint64_t revision = 0, parent = 0;
  std::uint64_t liveTriangles = 0, liveVertices = 0;
  Vec3 volumeOrigin;
  std::string label;
  std::vector<std::uint32_t> removed;
  struct NewVertex {
    std::uint32_t slot;
    Vec3 p;
  };
  std::vector<NewVertex> vertices;
  struct Added {
    std::uint32_t slot;
    Triangle corners;
  };
  std::vector<Added> triangles;
};

Record parse(const std::string& file, const std::string& payload) {
  PayloadReader in(file, payload.data(), payload.size());
  Record r;
  r.revision = in.get<std::uint64_t>();
  r.parent = in.get<std::uint64_t>();
  r.liveTriangles = in.get<std::uint64_t>();
  r.liveVertices = in.get<std::uint64_t>();
  r.volumeOrigin = {in.get<double>(), in.get<double>(), in.get<double>()};
  const std::uint32_t labelSize = in.get<std::uint32_t>();
  if (labelSize > kMaxLabel) throw InputError(file, "a record's label is longer than " + std::to_string(kMaxLabel) + " bytes");
  r.label = in.bytes(labelSize);
  r.removed.resize(in.count(4));
  for (std::uint32_t& s : r.removed) s = in.get<std::uint32_t>();
  r.vertices.resize(in.count(4 + 24));
  for (Record::NewVertex& v : r.vertices) {
    v.slot = in.get<std::uint32_t>();
    v.p = {in.get<double>(), in.get<double>(), in.get<double>()};
  }
  r.triangles.resize(in.count(16));
  for (Record::Added& t : r.triangles) {
    t.slot = in.get<std::uint32_t>();
    for (std::uint32_t& c : t.corners) c = in.get<std::uint32_t>();
  }
  if (!in.done()) throw InputError(file, "a record has data after its triangles");
  return r;
}

// What changed from `prev` to `next` (in their slots), as a record's payload.
std::string payloadFor(const BoneHistory::Entry& entry, std::uint64_t parent, const BoneState& prev) {
  const BoneState& next = entry.state;
  const SlotChanges changes = BoneState::changedTriangleSlots(prev, next);
  std::vector<std::uint32_t> newVertices;  // next's vertex slots that prev does not have at the same place
  std::unordered_map<std::uint32_t, bool> seen;
  for (std::uint32_t s : changes.added)
    for (std::uint32_t v : next.triangle(s)) {
      const bool existing = prev.isVertexLive(v) && prev.vertex(v) == next.vertex(v);
      if (!existing && seen.emplace(v, true).second) newVertices.push_back(v);
    }
  std::sort(newVertices.begin(), newVertices.end());
  std::string out;
  put(out, entry.revision);
  put(out, parent);
  put(out, std::uint64_t(next.liveTriangleCount()));
  put(out, std::uint64_t(next.liveVertexCount()));
  put(out, next.volumeOrigin().x);
  put(out, next.volumeOrigin().y);
  put(out, next.volumeOrigin().z);
  const std::string label = entry.label.substr(0, kMaxLabel);
  put(out, std::uint32_t(label.size()));
  out += label;
  put(out, std::uint32_t(changes.removed.size()));
  for (std::uint32_t s : changes.removed) put(out, s);
  put(out, std::uint32_t(newVertices.size()));
  for (std::uint32_t v : newVertices) {
    put(out, v);
    const Vec3& p = next.vertex(v);
    put(out, p.x);
    put(out, p.y);
    put(out, p.z);
  }
  put(out, std::uint32_t(changes.added.size()));
  for (std::uint32_t s : changes.added) {
    put(out, s);
    for (std::uint32_t v : next.triangle(s)) put(out, v);
  }
  return out;
}

struct Indexed {
  std::uint64_t revision, parent;
  std::uint64_t offset, size;  // of the payload
};

// The complete records of a journal's contents, in file order, and the length they span (a torn or damaged
// record and everything after it are left out: only a crash during an append leaves one, at the end).
std::vector<Indexed> indexRecords(const std::string& file, const std::string& data, std::uint64_t& validBytes) {
  if (data.size() < sizeof kMagic || std::memcmp(data.data(), kMagic, sizeof kMagic) != 0)
    throw InputError(file, "not a ReamSim history journal (no RSHJRNL1 header)");
  std::vector<Indexed> out;
  std::uint64_t at = sizeof kMagic;
  validBytes = at;
  while (data.size() - at >= kRecordOverhead) {
    std::uint32_t magic;
    std::uint64_t size;
    std::memcpy(&magic, data.data() + at, 4);
    std::memcpy(&size, data.data() + at + 4, 8);
    if (magic != kRecordMagic || size < 16 || size > data.size() - at - kRecordOverhead) break;
    std::uint64_t sum;
    std::memcpy(&sum, data.data() + at + 12 + size, 8);
    if (sum != fnv1a(data.data() + at + 12, size)) break;
    Indexed r;
    std::memcpy(&r.revision, data.data() + at + 12, 8);
    std::memcpy(&r.parent, data.data() + at + 20, 8);
    r.offset = at + 12;
    r.size = size;
    out.push_back(r);
    at += kRecordOverhead + size;
    validBytes = at;
  }
  return out;
}

// The file's bytes; with `missingIsEmpty`, none for a file that is not there (a journal about to be started).
std::string readWhole(const std::string& path, bool missingIsEmpty = false) {
  std::error_code ec;
  // A folder opens as a stream on Linux and fails only when read, with the standard library's own exception.
  if (std::filesystem::is_directory(path, ec)) throw InputError(path, "is a folder, not a history journal");
  std::ifstream in(path, std::ios::binary);
  if (!in && missingIsEmpty && !std::filesystem::exists(path, ec)) return {};
  if (!in) throw InputError(path, "cannot open the history journal");
  std::string data;
  try {
    data.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  } catch (const std::exception& e) {  // a read error the stream reports by throwing (libstdc++'s underflow)
    throw InputError(path, std::string("cannot read the history journal: ") + e.what());
  }
  if (in.bad()) throw InputError(path, "cannot read the history journal");
  return data;
}

// Replays records onto a state, mapping the written slots to the restored ones.
class Replay {
 public:
  explicit Replay(const std::string& file) : file_(file) {}
  BoneState apply(const Record& r) {
    const std::string where = "the record of revision " + std::to_string(r.revision);
    const bool first = !started_;
    started_ = true;
    MeshDelta delta;
    for (std::uint32_t s : r.removed) {
      const auto it = triangles_.find(s);
      if (it == triangles_.end())
        throw InputError(file_, where + " removes triangle slot " + std::to_string(s) + ", which is not there");
      delta.removedTriangles.push_back(it->second);
    }
    std::unordered_map<std::uint32_t, std::uint32_t> newIndex;
    for (const Record::NewVertex& v : r.vertices) {
      if (!isFinite(v.p)) throw InputError(file_, where + " has a non-finite vertex");
      if (!newIndex.emplace(v.slot, std::uint32_t(delta.addedVertices.size())).second)
        throw InputError(file_, where + " has vertex slot " + std::to_string(v.slot) + " twice");
      delta.addedVertices.push_back(v.p);
    }
    for (const Record::Added& t : r.triangles) {
      Triangle mapped;
      for (int i = 0; i < 3; ++i) {
        const std::uint32_t c = t.corners[i];
        if (auto it = newIndex.find(c); it != newIndex.end()) {
          mapped[i] = MeshDelta::newVertex(it->second);
        } else if (const auto known = vertices_.find(c); known != vertices_.end()) {
          mapped[i] = known->second;
        } else {
          throw InputError(file_, where + " uses vertex slot " + std::to_string(c) + ", which is not there");
        }
      }
      delta.addedTriangles.push_back(mapped);
    }
    DeltaPlacement placement;
    try {
      if (first) {
        // The first state as fromMesh makes it (its slots in the record's order), with the written one's volume
        // origin, which the volume of an open surface depends on.
        TriangleMesh mesh;
        mesh.vertices = std::move(delta.addedVertices);
        for (const Triangle& t : delta.addedTriangles)
          mesh.triangles.push_back({MeshDelta::newVertexIndex(t[0]), MeshDelta::newVertexIndex(t[1]), MeshDelta::newVertexIndex(t[2])});
        state_ = BoneState::fromMesh(mesh, BoneState::Ordering::Preserve, r.volumeOrigin);
        placement.vertexSlots.resize(mesh.vertices.size());
        for (std::uint32_t j = 0; j < mesh.vertices.size(); ++j) placement.vertexSlots[j] = state_.isVertexLive(j) ? j : kBad;
        placement.triangleSlots.resize(mesh.triangles.size());
        for (std::uint32_t i = 0; i < mesh.triangles.size(); ++i) placement.triangleSlots[i] = i;
      } else {
        state_ = state_.applyDelta(delta, &placement);
      }
    } catch (const std::invalid_argument& e) {
      throw InputError(file_, where + " does not apply: " + e.what());
    }
    if (state_.liveTriangleCount() != r.liveTriangles || state_.liveVertexCount() != r.liveVertices)
      throw InputError(file_, where + " does not give the state that was written (" +
                                  std::to_string(state_.liveTriangleCount()) + " triangles and " +
                                  std::to_string(state_.liveVertexCount()) + " vertices, against " +
                                  std::to_string(r.liveTriangles) + " and " + std::to_string(r.liveVertices) + ")");
    for (std::uint32_t s : r.removed) triangles_.erase(s);
    for (std::size_t i = 0; i < r.triangles.size(); ++i) triangles_[r.triangles[i].slot] = placement.triangleSlots[i];
    for (std::size_t j = 0; j < r.vertices.size(); ++j) {
      if (placement.vertexSlots[j] == kBad) throw InputError(file_, where + " has a new vertex that no triangle uses");
      vertices_[r.vertices[j].slot] = placement.vertexSlots[j];
    }
    return state_;
  }

 private:
  const std::string& file_;
  BoneState state_;
  bool started_ = false;
  // Written slot → restored slot. Hash maps, not arrays indexed by the written slot: a damaged record's slot
  // number cannot make them huge. A vertex that died stays mapped: no record names it again unless it is new.
  std::unordered_map<std::uint32_t, std::uint32_t> triangles_, vertices_;
};

// Appends `data` and has it on the disk (fdatasync) before returning true: a description written after this
// (recovery.json) must never name records the disk did not get.
bool appendSynced(const std::string& path, const std::string& data) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_APPEND);
  if (fd < 0) return false;
  bool ok = true;
  for (std::size_t done = 0; ok && done < data.size();) {
    const ssize_t n = ::write(fd, data.data() + done, data.size() - done);
    if (n < 0 && errno == EINTR) continue;
    ok = n > 0;
    if (ok) done += std::size_t(n);
  }
  ok = ok && ::fdatasync(fd) == 0;
  return ::close(fd) == 0 && ok;
}

}  // namespace

HistoryJournalWriter::HistoryJournalWriter(std::string path) : path_(std::move(path)) {
  const std::string data = readWhole(path_, /*missingIsEmpty=*/true);
  if (data.empty()) {
    std::ofstream out(path_, std::ios::binary | std::ios::trunc);
    out.write(kMagic, sizeof kMagic);
    out.flush();
    if (!out) throw InputError(path_, "cannot create the history journal");
    bytes_ = sizeof kMagic;
    return;
  }
  for (const Indexed& r : indexRecords(path_, data, bytes_)) written_.push_back(r.revision);
  std::sort(written_.begin(), written_.end());
  if (bytes_ < data.size() && ::truncate(path_.c_str(), off_t(bytes_)) != 0)
    throw InputError(path_, "cannot cut the history journal back to its complete records");
}

void HistoryJournalWriter::append(const std::vector<BoneHistory::Entry>& entries) {
  std::string out;
  std::vector<std::uint64_t> added;
  for (std::size_t k = 0; k < entries.size(); ++k) {
    if (std::binary_search(written_.begin(), written_.end(), entries[k].revision)) continue;
    static const BoneState kNothing;
    const std::string payload = payloadFor(entries[k], k ? entries[k - 1].revision : 0, k ? entries[k - 1].state : kNothing);
    put(out, kRecordMagic);
    put(out, std::uint64_t(payload.size()));
    out += payload;
    put(out, fnv1a(payload.data(), payload.size()));
    added.push_back(entries[k].revision);
  }
  if (out.empty()) return;
  if (!appendSynced(path_, out)) {
    [[maybe_unused]] const int ignored = ::truncate(path_.c_str(), off_t(bytes_));  // drop a partial append
    throw InputError(path_, "cannot append to the history journal and have it on the disk (disk full?)");
  }
  bytes_ += out.size();
  written_.insert(written_.end(), added.begin(), added.end());
  std::sort(written_.begin(), written_.end());
}

BoneHistory readHistoryJournal(const std::string& path, const std::vector<std::uint64_t>& revisions, std::size_t cursor) {
  if (revisions.empty()) throw InputError(path, "no history states were asked for");
  if (cursor >= revisions.size()) throw InputError(path, "the history's position is past its last state");
  const std::string data = readWhole(path);
  std::uint64_t validBytes = 0;
  std::unordered_map<std::uint64_t, Indexed> byRevision;
  for (const Indexed& r : indexRecords(path, data, validBytes)) byRevision.emplace(r.revision, r);
  Replay replay(path);
  std::optional<BoneHistory> history;
  for (std::size_t k = 0; k < revisions.size(); ++k) {
    const auto it = byRevision.find(revisions[k]);
    if (it == byRevision.end())
      throw InputError(path, "the state of revision " + std::to_string(revisions[k]) + " is not in the journal (" +
                                 std::to_string(byRevision.size()) + " complete records)");
    const std::uint64_t parent = k ? revisions[k - 1] : 0;
    if (it->second.parent != parent)
      throw InputError(path, "the state of revision " + std::to_string(revisions[k]) + " follows revision " +
                                 std::to_string(it->second.parent) + ", not " + std::to_string(parent));
    const Record r = parse(path, data.substr(it->second.offset, it->second.size));
    BoneState state = replay.apply(r);
    if (k == 0)
      history.emplace(std::move(state), r.label);
    else
      history->commit(std::move(state), r.label);
  }
  while (history->cursor() > cursor) history->undo();
  return std::move(*history);
}

std::vector<std::uint64_t> journalRevisions(const std::string& path) {
  const std::string data = readWhole(path);
  std::uint64_t validBytes = 0;
  std::vector<std::uint64_t> out;
  for (const Indexed& r : indexRecords(path, data, validBytes)) out.push_back(r.revision);
  return out;
}

}  // namespace reamsim
