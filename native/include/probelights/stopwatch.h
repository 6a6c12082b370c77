// Milliseconds since a start: the one clock behind every timing the core, the CLI and the module report.
#pragma once

#include <chrono>

namespace probelights {

class Stopwatch {
 public:
  double ms() const { return std::chrono::duration<double, std::milli>(Clock::now() - start_).count(); }
  void restart() { start_ = Clock::now(); }

 private:
  using Clock = std::chrono::steady_clock;
  Clock::time_point start_ = Clock::now();
};

}  // namespace probelights
