// Every file the command line writes, written whole or not at all. A file goes to a temporary name beside
// its target (same folder, so the rename cannot cross filesystems), is flushed to the disk (fsync), then
// renamed over the target: a reader, a crash, a full disk or Ctrl-C leaves the old file or the new one,
// never half of one, and a failed write is an Error naming the file and the system's reason.
#pragma once

#include <functional>
#include <string>
#include <string_view>

namespace probelights::cli {

// Writes `bytes` to `path` whole. A target that exists and is not a regular file (a FIFO, /dev/null, a
// terminal) is written directly: renaming over it would replace the device.
void writeWhole(const std::string& path, std::string_view bytes);

// The same for a file another library writes by name (a PNG through OpenImageIO): write(tmp) writes the
// file at `tmp`, which ends in the target's extension.
void writeWholeVia(const std::string& path, const std::function<void(const std::string& tmp)>& write);

// An image written by write(tmp) through OpenImageIO, then read back whole before it replaces the target:
// an image writer that does not report a failed write (a full disk) cannot leave a truncated picture.
void writeImageWhole(const std::string& path, const std::function<void(const std::string& tmp)>& write);

// Writes `bytes` to standard output and flushes it; an Error when they did not all go out (a closed pipe,
// a full disk behind a redirection).
void writeStdout(std::string_view bytes);

// On SIGINT, SIGTERM or SIGHUP, temporary files not yet renamed are removed before the process ends as the
// signal ends it. With `stopAfter`, the first signal only sets *stopAfter (work in progress finishes and the
// caller stops at its next check, writing what it has done); a second one ends the process.
void removeTemporariesOnSignal(volatile bool* stopAfter = nullptr);

// Whether `a` and `b` name the same existing file (false when either does not exist).
bool sameFile(const std::string& a, const std::string& b);

}  // namespace probelights::cli
