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
Kept kept[2];
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
    // An empty slot, else the one given back longer ago: the last two tables' buffers are kept.
    Kept* slot = !kept[0].memory                        ? &kept[0]
                 : !kept[1].memory                      ? &kept[1]
                 : kept[0].released <= kept[1].released ? &kept[0]
                                                        : &kept[1];
    std::swap(slot->memory, memory);
    slot->capacity = capacity;
    slot->released = ++releases;
  }
  std::free(memory);  // the one not kept (null if the slot was empty)
}

void releaseKeptBuffers() {
  std::lock_guard<std::mutex> lock(keptMutex);
  for (Kept& k : kept) {
    std::free(k.memory);
    k = {};
  }
}

}  // namespace probelights
