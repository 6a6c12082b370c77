// Work that runs beside other work of its kind (a library's loads: batch.h; a caller's own pool of bakes)
// keeps its loops on its own thread instead of sharing the thread pool (parallel loops run inline): no
// waiting on each other's tasks, and a summed-area table built row after row is written once instead of
// twice (summed_area_table.h). Results are bit-identical either way. For the scope of one OnOneThread, on the
// thread that made it.
#pragma once

namespace probelights {

inline thread_local bool oneThread = false;

class OnOneThread {
 public:
  OnOneThread() : before_(oneThread) { oneThread = true; }
  ~OnOneThread() { oneThread = before_; }
  OnOneThread(const OnOneThread&) = delete;
  OnOneThread& operator=(const OnOneThread&) = delete;

 private:
  bool before_;
};

}  // namespace probelights
