// Built into the portable core only (the other build loops on OpenImageIO's pool: parallel.h).
#if !PROBELIGHTS_PARALLEL_OIIO
#include "thread_pool.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>

namespace probelights {

namespace {

thread_local bool inLoop = false;  // this thread is running a body of the pool's loop

// A worker that finished a loop watches for the next one for kSpin before it sleeps: waking a sleeping thread
// costs ~40 us here, as much as a small loop's work, and the refit runs its loops back to back.
constexpr auto kSpin = std::chrono::microseconds(300);

class Pool {
 public:
  explicit Pool(int workers) : workers_(workers) {
    for (int t = 0; t < workers; ++t) threads_.emplace_back([this] { work(); });
  }

  bool run(std::int64_t n, void (*body)(void*, std::int64_t), void* context) {
    if (workers_ == 0 || inLoop) return false;
    if (busy_.exchange(true, std::memory_order_acquire)) return false;
    body_ = body, context_ = context, n_ = n;
    next_.store(0, std::memory_order_relaxed);
    pending_.store(workers_, std::memory_order_relaxed);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      generation_.fetch_add(1, std::memory_order_release);
    }
    wake_.notify_all();
    drain();
    while (pending_.load(std::memory_order_acquire) > 0) std::this_thread::yield();
    busy_.store(false, std::memory_order_release);
    return true;
  }

 private:
  void drain() {
    inLoop = true;
    for (std::int64_t i; (i = next_.fetch_add(1, std::memory_order_relaxed)) < n_;) body_(context_, i);
    inLoop = false;
  }

  void work() {
    std::uint64_t seen = 0;
    for (;;) {
      const auto until = std::chrono::steady_clock::now() + kSpin;
      while (generation_.load(std::memory_order_acquire) == seen && std::chrono::steady_clock::now() < until)
        std::this_thread::yield();
      if (generation_.load(std::memory_order_acquire) == seen) {
        std::unique_lock<std::mutex> lock(mutex_);
        wake_.wait(lock, [&] { return generation_.load(std::memory_order_acquire) != seen; });
      }
      seen = generation_.load(std::memory_order_acquire);
      drain();
      pending_.fetch_sub(1, std::memory_order_release);
    }
  }

  // No pthread_detach or pthread_mutex_trylock: the add-on's module must not need glibc 2.34's versions of
  // them (addon/CMakeLists.txt). The threads are never joined: the pool lives as long as the process.
  const int workers_;
  std::vector<std::thread> threads_;
  std::atomic<bool> busy_{false};  // one loop at a time
  std::mutex mutex_;               // sleeping workers wait on wake_ under it
  std::condition_variable wake_;
  std::atomic<std::uint64_t> generation_{0};  // one more for every loop
  std::atomic<int> pending_{0};               // workers not yet done with the current loop
  void (*body_)(void*, std::int64_t) = nullptr;
  void* context_ = nullptr;
  std::int64_t n_ = 0;
  std::atomic<std::int64_t> next_{0};
};

}  // namespace

bool runOnPool(std::int64_t n, void (*body)(void*, std::int64_t), void* context) {
  // Never destroyed: its workers wait on it until the process ends.
  static Pool* pool = new Pool(static_cast<int>(std::max(1u, std::thread::hardware_concurrency())) - 1);
  return pool->run(n, body, context);
}

}  // namespace probelights
#endif
