// Every failure the library reports to a user: one line that says what is wrong and, where it helps, what to
// do.
#pragma once

#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace probelights {

// What gets past a failure: an option of the request (request.h; or the probe's projection) and the values
// that do it. The core never spells it: each shell says it in its own words (describe), the CLI as
// --nonfinite zero, the module as nonfinite='zero', the add-on as its panel's setting.
struct Remedy {
  std::string purpose;              // what the option would do, e.g. "to read them as 0"
  std::string option;               // its name, e.g. "nonfinite"
  std::vector<std::string> values;  // any of these, e.g. {"zero"}
};

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
  Error(const std::string& message, Remedy remedy)
      : std::runtime_error(message), remedy_(std::make_shared<const Remedy>(std::move(remedy))) {}
  // The same failure with `context` before its message (e.g. "probe 'sky.exr': "), its remedy kept.
  Error within(const std::string& context) const {
    Error e(context + what());
    e.remedy_ = remedy_;
    return e;
  }
  const Remedy* remedy() const { return remedy_.get(); }
  std::shared_ptr<const Remedy> sharedRemedy() const { return remedy_; }

 private:
  std::shared_ptr<const Remedy> remedy_;
};

// A failure as a shell tells it: the message, then "; " + the remedy's purpose + ": " + the shell's spelling.
inline std::string describe(const std::string& message, const Remedy* remedy,
                            const std::function<std::string(const Remedy&)>& spell) {
  return remedy ? message + "; " + remedy->purpose + ": " + spell(*remedy) : message;
}
inline std::string describe(const Error& e, const std::function<std::string(const Remedy&)>& spell) {
  return describe(e.what(), e.remedy(), spell);
}

}  // namespace probelights
