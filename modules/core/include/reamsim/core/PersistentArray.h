#pragma once
// Persistent (immutable-by-value) chunked array: a copy is O(1) and shares all storage; set(),
// push_back() and pop_back() copy only the chunk they touch (and the chunk table, O(size/N) pointers),
// so older copies never change. This is what lets the bone history keep N states without N meshes.
//
// Mutation happens in place when this array is the sole owner of the table and the chunk (checked by
// use_count), which keeps building an array by push_back O(size). Copies may be read concurrently
// from several threads; one instance must not be mutated while another thread uses that instance.
#include <atomic>
#include <cstddef>
#include <memory>
#include <stdexcept>
#include <vector>

namespace reamsim {

template <class T, std::size_t N = 1024>
class PersistentArray {
  static_assert(N > 0, "chunk size must be positive");

 public:
  static constexpr std::size_t kChunkSize = N;

  PersistentArray() : table_(std::make_shared<Table>()) {}

  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  const T& operator[](std::size_t i) const { return (*(*table_)[i / N])[i % N]; }
  const T& at(std::size_t i) const {
    if (i >= size_) throw std::out_of_range("PersistentArray::at");
    return (*this)[i];
  }
  const T& back() const { return (*this)[size_ - 1]; }

  void set(std::size_t i, const T& value) {
    if (i >= size_) throw std::out_of_range("PersistentArray::set");
    mutableChunk(i / N)[i % N] = value;
  }
  void push_back(const T& value) {
    if (size_ % N == 0) {
      auto chunk = std::make_shared<Chunk>();
      chunk->reserve(N);
      mutableTable().push_back(std::move(chunk));
    }
    mutableChunk(size_ / N).push_back(value);
    ++size_;
  }
  void pop_back() {
    if (size_ == 0) throw std::out_of_range("PersistentArray::pop_back");
    --size_;
    if (size_ % N == 0) {
      mutableTable().pop_back();  // never copies the dropped chunk
    } else {
      mutableChunk(size_ / N).pop_back();
    }
  }
  void clear() {
    table_ = std::make_shared<Table>();
    size_ = 0;
  }

  // Calls f(element) for every element, chunk by chunk (faster than operator[] in a loop).
  template <class F>
  void forEach(F&& f) const {
    for (const auto& chunk : *table_)
      for (const T& v : *chunk) f(v);
  }

  std::size_t chunkCount() const { return table_->size(); }
  // Identity of chunk c: equal pointers in two arrays mean shared storage.
  const void* chunkIdentity(std::size_t c) const { return (*table_)[c].get(); }
  // Calls f(identity, bytes) for every heap block: the chunk table and each chunk. Counting blocks by
  // identity across arrays measures the memory actually held.
  template <class F>
  void visitStorage(F&& f) const {
    f(static_cast<const void*>(table_.get()), sizeof(Table) + table_->capacity() * sizeof(ChunkPtr));
    for (const auto& chunk : *table_)
      f(static_cast<const void*>(chunk.get()), sizeof(Chunk) + chunk->capacity() * sizeof(T));
  }

 private:
  using Chunk = std::vector<T>;  // holds at most N elements, capacity N
  using ChunkPtr = std::shared_ptr<Chunk>;  // never mutated once shared (see mutableChunk)
  using Table = std::vector<ChunkPtr>;

  // use_count() == 1 means nobody else can observe the block; the acquire fence orders our writes
  // after other threads' reads of the block that happened before they released their reference.
  template <class P>
  static bool soleOwner(const std::shared_ptr<P>& p) {
    if (p.use_count() != 1) return false;
    std::atomic_thread_fence(std::memory_order_acquire);
    return true;
  }
  Table& mutableTable() {
    if (!soleOwner(table_)) table_ = std::make_shared<Table>(*table_);
    return *table_;
  }
  Chunk& mutableChunk(std::size_t c) {
    ChunkPtr& chunk = mutableTable()[c];
    if (!soleOwner(chunk)) {
      auto copy = std::make_shared<Chunk>();
      copy->reserve(N);
      copy->assign(chunk->begin(), chunk->end());
      chunk = std::move(copy);
    }
    return *chunk;
  }

  std::shared_ptr<Table> table_;
  std::size_t size_ = 0;
};

}  // namespace reamsim
