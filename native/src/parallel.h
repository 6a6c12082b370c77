// Parallel loops over OpenImageIO's thread pool.
#pragma once

#include <OpenImageIO/parallel.h>

#include <cstdint>

namespace probelights {

// Runs task(i) for i in [0, n) on the pool. OpenImageIO's parallel_for keeps ranges of fewer than 1024 items
// on one thread by default (paropt's minitems); our items (rows of cells, regions) are each large, so allow
// one per task.
template <class Task>
void parallelFor(std::int64_t n, Task&& task) {
  OIIO::parallel_for(std::int64_t{0}, n, OIIO::function_view<void(std::int64_t)>(task),
                     OIIO::paropt(0, OIIO::paropt::SplitDir::Y, 1));
}

}  // namespace probelights
