// Fresh memory: the first write to each page of a new allocation makes the kernel map it (~0.4 ms per MB on
// one thread here), which for big pixel buffers costs as much as reading the image.
#pragma once

#include <cstddef>

namespace probelights {

// Writes one byte (zero) to every page of [memory, memory + bytes) from all threads, so the kernel maps the
// pages in parallel: 537 MB took 206 ms on one thread and 112 ms on two here. For a new buffer that a single
// thread is about to fill (Blender's foreach_get fills the add-on's read buffer); its contents are undefined
// afterwards, as before.
void touchPages(void* memory, std::size_t bytes);

}  // namespace probelights
