#include "probelights/memory.h"

#include <cstdint>
#include <cstdlib>
#include <mutex>
#include <new>

#include "parallel.h"

namespace probelights {

void touchPages(void* memory, std::size_t bytes) {
  constexpr std::size_t kPage = 4096, kChunk = std::size_t{4} << 20;  // 4 MB a task
  auto* p = static_cast<volatile unsigned char*>(memory);
  const auto chunks = static_cast<std::int64_t>((bytes + kChunk - 1) / kChunk);
  parallelFor(chunks, [&](std::int64_t c) {
    const std::size_t begin = static_cast<std::size_t>(c) * kChunk;
    const std::size_t end = begin + kChunk < bytes ? begin + kChunk : bytes;
    for (std::size_t i = begin; i < end; i += kPage) p[i] = 0;
  });
}

namespace {

struct Kept {
  void* memory = nullptr;
  std::size_t capacity = 0;
  std::uint64_t released = 0;  // when it was given back: the older of two full slots makes room
};
std::mutex keptMutex;
Kept kept[4];
std::uint64_t releases = 0;

}  // namespace

void* takeBuffer(std::size_t bytes, std::size_t* capacity) {
  {
    std::lock_guard<std::mutex> lock(keptMutex);
    for (Kept& k : kept)
      if (k.memory && k.capacity >= bytes && k.capacity / 2 <= bytes) {
        void* memory = k.memory;
        *capacity = k.capacity;
        k = {};
        return memory;
      }
  }
  void* memory = std::malloc(bytes ? bytes : 1);
  if (!memory) throw std::bad_alloc();
  *capacity = bytes;
  return memory;
}

void KeptBufferDeleter::operator()(void* memory) const {
  if (!memory) return;
  {
    std::lock_guard<std::mutex> lock(keptMutex);
    // Up to four buffers are kept (a library of small probes has three in flight, each an image and a table),
    // of which at most three of 32 MB or more (the add-on's click at 4K and 8K: a 2048 x 1024 grid's table,
    // 84 MB, its cell sums and its energy^2 sums, 64 MB each): a big one replaces the oldest big one once
    // three are kept, anything else an empty slot or the one given back longest ago.
    constexpr std::size_t kBig = std::size_t{32} << 20;
    constexpr int kMaxBig = 3;
    const bool big = capacity >= kBig;
    int bigKept = 0;
    for (const Kept& k : kept) bigKept += k.memory && k.capacity >= kBig;
    Kept* slot = nullptr;
    for (Kept& k : kept) {
      if (big && bigKept >= kMaxBig && k.capacity < kBig) continue;  // (an empty slot's capacity is 0)
      if (!k.memory) {
        slot = &k;
        break;
      }
      if (!slot || k.released < slot->released) slot = &k;
    }
    std::swap(slot->memory, memory);
    slot->capacity = capacity;
    slot->released = ++releases;
  }
  std::free(memory);  // the one not kept (null if the slot was empty)
}

std::size_t keptBytes() {
  std::lock_guard<std::mutex> lock(keptMutex);
  std::size_t bytes = 0;
  for (const Kept& k : kept) bytes += k.memory ? k.capacity : 0;
  return bytes;
}

void releaseKeptBuffers() {
  std::lock_guard<std::mutex> lock(keptMutex);
  for (Kept& k : kept) {
    std::free(k.memory);
    k = {};
  }
}

}  // namespace probelights
