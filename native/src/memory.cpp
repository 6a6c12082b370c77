#include "probelights/memory.h"

#include <cstdint>

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

}  // namespace probelights
