// The portable build's threads (parallel.h): hardware_concurrency - 1 workers, started on first use and kept
// for the process, so a parallel loop costs a wake-up (a few microseconds) instead of starting threads
// (~20-50 us each; the refit's direction moves run thousands of small loops).
#pragma once

#include <cstdint>

namespace probelights {

// Runs body(context, i) for i in [0, n) on the workers and the calling thread, and returns when all are done.
// Returns false without running anything when the pool has no workers, is running another caller's loop, or
// is called from inside one of its own loops: the caller then runs the loop itself.
bool runOnPool(std::int64_t n, void (*body)(void*, std::int64_t), void* context);

}  // namespace probelights
