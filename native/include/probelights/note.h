// A line the core tells the user about a bake, typed so that no shell reads its words to place it: what kind
// of line it is, the line, and the figures behind it.
#pragma once

#include <string>

namespace probelights {

enum class NoteKind {
  Reading,  // how the probe was read: its projection, channels, colour decoding, data window, bands
  Chosen,   // what the bake chose where the request let it: the count for a tolerance, the cut of both
  Warning,  // what did not go as asked or as usual: fewer lights, no refit, a tolerance not met, NaN/Inf read
            // as 0, negative samples, a black probe
};

// "reading", "chosen", "warning": the JSON's and the module's words for a kind.
inline const char* toString(NoteKind kind) {
  return kind == NoteKind::Chosen ? "chosen" : kind == NoteKind::Warning ? "warning" : "reading";
}

struct Note {
  NoteKind kind = NoteKind::Reading;
  std::string text;  // one line
  // The figures behind it, or "" (the CLI shows them in parentheses; the panel does not).
  std::string detail = {};
  std::string line() const { return detail.empty() ? text : text + " (" + detail + ")"; }
  bool operator==(const Note&) const = default;
};

}  // namespace probelights
