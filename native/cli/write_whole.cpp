#include "write_whole.h"

#include <OpenImageIO/imageio.h>
#include <fcntl.h>
#include <sys/stat.h>
#ifdef _WIN32
#include <io.h>
#include <process.h>
#define WIN32_LEAN_AND_MEAN
#define NOMINMAX
#include <windows.h>
#else
#include <unistd.h>
#endif

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <vector>

#include "probelights/error.h"

namespace probelights::cli {

namespace {

namespace fs = std::filesystem;

// The system calls below, each platform's. Windows (the Python package's module there): no close-on-exec or
// mode bits, binary mode always (text mode would write \r\n), _commit flushes to the disk as fsync does, and
// a rename that replaces its target is MoveFileEx's (C's rename refuses an existing target there).
#ifdef _WIN32
int openFile(const char* path, int flags, int mode = 0) {
  return _open(path, flags | _O_BINARY | _O_NOINHERIT, mode);
}
long long writeSome(int fd, const char* p, std::size_t n) {
  return _write(fd, p, static_cast<unsigned>(std::min<std::size_t>(n, std::size_t{1} << 30)));
}
int syncFile(int fd) { return _commit(fd); }
int setMode(int, unsigned) { return 0; }
int closeFile(int fd) { return _close(fd); }
int processId() { return _getpid(); }
void removeFile(const char* path) { _unlink(path); }
bool replaceFile(const char* from, const char* to) {
  if (MoveFileExA(from, to, MOVEFILE_REPLACE_EXISTING | MOVEFILE_WRITE_THROUGH)) return true;
  errno = GetLastError() == ERROR_ACCESS_DENIED ? EACCES : EIO;
  return false;
}
constexpr int kCloseOnExec = 0;
#else
int openFile(const char* path, int flags, int mode = 0) { return ::open(path, flags, mode); }
long long writeSome(int fd, const char* p, std::size_t n) { return ::write(fd, p, n); }
int syncFile(int fd) { return ::fsync(fd); }
int setMode(int fd, unsigned mode) { return ::fchmod(fd, static_cast<mode_t>(mode)); }
int closeFile(int fd) { return ::close(fd); }
int processId() { return static_cast<int>(::getpid()); }
void removeFile(const char* path) { ::unlink(path); }
bool replaceFile(const char* from, const char* to) { return std::rename(from, to) == 0; }
constexpr int kCloseOnExec = O_CLOEXEC;
#endif

// The temporary files being written, for the signal handler to remove: fixed slots of strdup'd paths, read
// with atomic loads only (async-signal-safe, as are unlink and raise).
constexpr int kSlots = 16;
std::atomic<char*> temporaries[kSlots];
volatile bool* stopFlag = nullptr;
std::atomic<int> signalsSeen{0};

void onSignal(int sig) {
  if (stopFlag && signalsSeen.fetch_add(1) == 0) {
    *stopFlag = true;
    return;
  }
  for (auto& slot : temporaries)
    if (char* p = slot.load()) removeFile(p);
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

// A temporary file's path, registered for removal on a signal while it lives.
class Temporary {
 public:
  explicit Temporary(const fs::path& target) {
    static std::atomic<unsigned> counter{0};
    const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
    // .NAME.part-PID-N.EXT: hidden, unique, and ending in the target's extension (OpenImageIO picks the
    // format by it). Appended piece by piece: GCC 12 warns (-Wrestrict, falsely) on the one-expression form.
    std::string name = ".";
    name += target.filename().string();
    name += ".part-" + std::to_string(processId()) + "-" + std::to_string(counter++);
    name += target.extension().string();
    path_ = (dir / name).string();
    char* copy = strdup(path_.c_str());
    for (auto& slot : temporaries) {
      char* expected = nullptr;
      if (slot.compare_exchange_strong(expected, copy)) {
        slot_ = &slot;
        return;
      }
    }
    std::free(copy);  // every slot taken (never, with one write at a time): removed by the destructor only
  }
  ~Temporary() {
    std::error_code ec;
    if (!renamed_) fs::remove(path_, ec);
    if (slot_) std::free(slot_->exchange(nullptr));
  }
  Temporary(const Temporary&) = delete;
  Temporary& operator=(const Temporary&) = delete;
  const std::string& path() const { return path_; }
  void renamedTo(const std::string& target) {
    if (!replaceFile(path_.c_str(), target.c_str())) {
      const int e = errno;
      throw Error("cannot write '" + target + "': " + std::strerror(e));
    }
    renamed_ = true;
  }

 private:
  std::string path_;
  std::atomic<char*>* slot_ = nullptr;
  bool renamed_ = false;
};

Error writeError(const std::string& path, int e) {
  return Error("cannot write '" + path + "': " + std::strerror(e));
}

// Writes all of `bytes` to the open descriptor; false with errno set when they did not all go.
bool writeAll(int fd, std::string_view bytes) {
  while (!bytes.empty()) {
    const long long n = writeSome(fd, bytes.data(), bytes.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      if (n == 0) errno = EIO;
      return false;
    }
    bytes.remove_prefix(static_cast<std::size_t>(n));
  }
  return true;
}

// What the target is: missing, a regular file (mode kept for its replacement), or something else.
enum class Target { Missing, File, Other };
Target inspect(const std::string& path, unsigned* mode) {
  struct stat st {};
  if (stat(path.c_str(), &st) != 0) return Target::Missing;
  if (S_ISDIR(st.st_mode)) throw Error("cannot write '" + path + "': it is a directory");
  if (!S_ISREG(st.st_mode)) return Target::Other;
  *mode = st.st_mode & 07777;
  return Target::File;
}

// Flushes an existing file at `path` to the disk; the system's error otherwise.
void syncPath(const std::string& path, unsigned mode, const std::string& target) {
  const int fd = openFile(path.c_str(), O_RDWR | kCloseOnExec);
  if (fd < 0) throw writeError(target, errno);
  const bool ok = syncFile(fd) == 0 && (mode == 0 || setMode(fd, mode) == 0);
  const int e = errno;
  closeFile(fd);
  if (!ok) throw writeError(target, e);
}

// A symbolic link is written through: the file it names is replaced, the link kept.
std::string resolved(const std::string& path) {
  std::error_code ec;
  if (fs::is_symlink(path, ec)) {
    const fs::path target = fs::weakly_canonical(path, ec);
    if (!ec) return target.string();
  }
  return path;
}

}  // namespace

void writeWhole(const std::string& pathIn, std::string_view bytes) {
  if (pathIn.empty()) throw Error("an output file name is empty");
  const std::string path = resolved(pathIn);
  unsigned mode = 0;
  if (inspect(path, &mode) == Target::Other) {
    const int fd = openFile(path.c_str(), O_WRONLY | kCloseOnExec);
    if (fd < 0) throw writeError(pathIn, errno);
    const bool ok = writeAll(fd, bytes);
    const int e = errno;
    if (closeFile(fd) != 0 || !ok) throw writeError(pathIn, ok ? errno : e);
    return;
  }
  Temporary tmp{fs::path(path)};
  const int fd = openFile(tmp.path().c_str(), O_WRONLY | O_CREAT | O_EXCL | kCloseOnExec, 0666);
  if (fd < 0) throw writeError(pathIn, errno);
  bool ok = writeAll(fd, bytes) && syncFile(fd) == 0 && (mode == 0 || setMode(fd, mode) == 0);
  int e = errno;
  if (closeFile(fd) != 0 && ok) ok = false, e = errno;
  if (!ok) throw writeError(pathIn, e);
  tmp.renamedTo(path);
}

void writeWholeVia(const std::string& pathIn, const std::function<void(const std::string& tmp)>& write) {
  if (pathIn.empty()) throw Error("an output file name is empty");
  const std::string path = resolved(pathIn);
  unsigned mode = 0;
  if (inspect(path, &mode) == Target::Other) return write(path);
  Temporary tmp{fs::path(path)};
  write(tmp.path());
  syncPath(tmp.path(), mode, pathIn);
  tmp.renamedTo(path);
}

void writeImageWhole(const std::string& path, const std::function<void(const std::string& tmp)>& write) {
  writeWholeVia(path, [&](const std::string& tmp) {
    write(tmp);
    if (tmp == path) return;  // a device or FIFO: nothing to read back
    auto in = OIIO::ImageInput::open(tmp);
    std::vector<float> pixels;
    if (in) pixels.resize(static_cast<std::size_t>(in->spec().image_pixels()) * in->spec().nchannels);
    const bool whole = in &&
                       in->read_image(0, 0, 0, in->spec().nchannels, OIIO::TypeDesc::FLOAT, pixels.data()) &&
                       !in->has_error();
    if (!whole) {
      std::error_code ec;
      const bool full =
          fs::space(fs::path(tmp).parent_path().empty() ? fs::path(".") : fs::path(tmp).parent_path(), ec)
                  .available == 0 &&
          !ec;
      throw Error("cannot write '" + path + "': " +
                  (full ? std::string(std::strerror(ENOSPC)) : "the image written does not read back whole"));
    }
  });
}

void writeStdout(std::string_view bytes) {
  // ferror too: a failed write flushed earlier by somebody else (a library's fflush(NULL)) is still a
  // failure.
  if (std::fwrite(bytes.data(), 1, bytes.size(), stdout) != bytes.size() || std::fflush(stdout) != 0 ||
      std::ferror(stdout)) {
    const int e = errno;
    throw Error(std::string("cannot write to standard output: ") + std::strerror(e));
  }
}

void removeTemporariesOnSignal(volatile bool* stopAfter) {
  stopFlag = stopAfter;
#ifdef SIGHUP
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) std::signal(sig, onSignal);
#else
  for (int sig : {SIGINT, SIGTERM}) std::signal(sig, onSignal);
#endif
}

bool sameFile(const std::string& a, const std::string& b) {
  std::error_code ec;
  return fs::equivalent(a, b, ec);  // false when either does not exist
}

}  // namespace probelights::cli
