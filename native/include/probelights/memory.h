// Fresh memory: the first write to each page of a new allocation makes the kernel map it, which for big pixel
// buffers and tables costs as much as reading the image (docs/results/accuracy.md: BM_FirstTouch).
#pragma once

#include <cstddef>
#include <memory>

namespace probelights {

// Writes one byte (zero) to every page of [memory, memory + bytes) from all threads, so the kernel maps the
// pages in parallel (about twice as fast on two threads as on one). For a new buffer that a single
// thread is about to fill (Blender's foreach_get fills the add-on's read buffer); its contents are undefined
// afterwards, as before.
void touchPages(void* memory, std::size_t bytes);

// Buffers for big tables (summed-area tables, a grid's cell sums) and images read from files, kept after use
// for the next one that fits (each used for one of at least half its size), so bakes in one process (the
// add-on's clicks, the tradeoff, a library) do not pay the kernel's first touch again (a 2048 x 1024
// full-resolution table is 84 MB). Up to four are kept, of which at most three of 32 MB or more (a click at
// 4K or 8K takes three). Their contents are undefined when taken.
// releaseKeptBuffers() gives them back (the add-on calls it once it has not baked for a minute); keptBytes()
// says how much is kept.
struct KeptBufferDeleter {
  std::size_t capacity = 0;
  void operator()(void* memory) const;
};
template <class T>
using KeptArray = std::unique_ptr<T[], KeptBufferDeleter>;

void* takeBuffer(std::size_t bytes, std::size_t* capacity);
void releaseKeptBuffers();
std::size_t keptBytes();

// An array of n trivial T (doubles, plain structs of doubles) in a kept buffer.
template <class T>
KeptArray<T> keptArray(std::size_t n) {
  std::size_t capacity = 0;
  void* memory = takeBuffer(n * sizeof(T), &capacity);
  return KeptArray<T>(static_cast<T*>(memory), KeptBufferDeleter{capacity});
}

}  // namespace probelights
