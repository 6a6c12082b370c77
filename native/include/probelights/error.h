// Every failure the library reports to a user: one line that says what is wrong and, where it helps, what to
// do.
#pragma once

#include <stdexcept>
#include <string>

namespace probelights {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace probelights
