// Parallel loops: OpenImageIO's thread pool where the library links OpenImageIO (CLI, tests, the full Python
// module), or our own pool of std::threads (thread_pool.h) in the portable build that the Blender add-on
// loads (it must link nothing but libc: see native/CMakeLists.txt). Every caller computes item i from i
// alone, so results are bit-identical whichever backend runs and however many threads it has.
#pragma once

#include <algorithm>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "probelights/one_thread.h"

#if PROBELIGHTS_PARALLEL_OIIO
#include <OpenImageIO/parallel.h>
#else
#include "thread_pool.h"
#endif

namespace probelights {

// Runs task(i) for i in [0, n).
template <class Task>
void parallelFor(std::int64_t n, Task&& task) {
  if (oneThread) {  // one_thread.h
    for (std::int64_t i = 0; i < n; ++i) task(i);
    return;
  }
#if PROBELIGHTS_PARALLEL_OIIO
  // OpenImageIO's parallel_for keeps ranges of fewer than 1024 items on one thread by default (paropt's
  // minitems); our items (rows of cells, regions) are each large, so allow one per task.
  OIIO::parallel_for(std::int64_t{0}, n, OIIO::function_view<void(std::int64_t)>(task),
                     OIIO::paropt(0, OIIO::paropt::SplitDir::Y, 1));
#else
  // The pool's threads take the next item from a shared counter (items differ in cost); tiny loops, and
  // loops inside the pool's own loops, stay on the caller's thread.
  auto call = [&task](std::int64_t i) { task(i); };
  if (n > 1 && runOnPool(
                   n, [](void* c, std::int64_t i) { (*static_cast<decltype(call)*>(c))(i); }, &call))
    return;
  for (std::int64_t i = 0; i < n; ++i) task(i);
#endif
}

// The ordered parallel reduction: part(i) for i in [0, n) in parallel (each from i alone), then
// combine(total, part(i)) for i = 0, 1, ..., n - 1 on the caller's thread, so the result is bit-identical
// whatever the thread count. Returns the total, starting from `init`.
template <class T, class Part, class Combine>
T parallelReduce(std::int64_t n, T init, Part&& part, Combine&& combine) {
  std::vector<std::decay_t<decltype(part(std::int64_t{0}))>> parts(
      static_cast<std::size_t>(std::max<std::int64_t>(n, 0)));
  parallelFor(n, [&](std::int64_t i) { parts[static_cast<std::size_t>(i)] = part(i); });
  for (std::int64_t i = 0; i < n; ++i) combine(init, std::move(parts[static_cast<std::size_t>(i)]), i);
  return init;
}

}  // namespace probelights
