// Linked only into the macOS modules (addon/CMakeLists.txt). They carry libc++ statically (zig c++), and
// its replaceable operator new and delete are exported weak definitions; zig's Mach-O linker has no
// -exported_symbol to keep them in, so the module would offer them to dyld's weak coalescing with every
// image loaded after it. Defined here, hidden, they win over libc++'s weak ones at link time: the module's
// allocations (and its libc++'s) go to malloc and free inside it, and it exports PyInit__probelights alone
// (tests/python/test_platform_modules.py).
#include <cstdlib>
#include <new>

// Compiled with -fvisibility-global-new-delete=force-hidden (clang 17+): <new>'s declarations say default.
#define PROBELIGHTS_HIDDEN __attribute__((visibility("hidden")))

namespace {

void* allocate(std::size_t bytes) {
  if (void* p = std::malloc(bytes ? bytes : 1)) return p;
  throw std::bad_alloc();
}

void* allocate(std::size_t bytes, std::align_val_t alignment) {
  void* p = nullptr;
  const std::size_t a = static_cast<std::size_t>(alignment) < sizeof(void*)
                            ? sizeof(void*)
                            : static_cast<std::size_t>(alignment);
  if (posix_memalign(&p, a, bytes ? bytes : 1) != 0) throw std::bad_alloc();
  return p;
}

template <class... A>
void* noThrow(A... a) noexcept {
  try {
    return allocate(a...);
  } catch (...) {
    return nullptr;
  }
}

}  // namespace

PROBELIGHTS_HIDDEN void* operator new(std::size_t n) { return allocate(n); }
PROBELIGHTS_HIDDEN void* operator new[](std::size_t n) { return allocate(n); }
PROBELIGHTS_HIDDEN void* operator new(std::size_t n, const std::nothrow_t&) noexcept { return noThrow(n); }
PROBELIGHTS_HIDDEN void* operator new[](std::size_t n, const std::nothrow_t&) noexcept { return noThrow(n); }
PROBELIGHTS_HIDDEN void* operator new(std::size_t n, std::align_val_t a) { return allocate(n, a); }
PROBELIGHTS_HIDDEN void* operator new[](std::size_t n, std::align_val_t a) { return allocate(n, a); }
PROBELIGHTS_HIDDEN void* operator new(std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
  return noThrow(n, a);
}
PROBELIGHTS_HIDDEN void* operator new[](std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
  return noThrow(n, a);
}
PROBELIGHTS_HIDDEN void operator delete(void* p) noexcept { std::free(p); }
PROBELIGHTS_HIDDEN void operator delete[](void* p) noexcept { std::free(p); }
PROBELIGHTS_HIDDEN void operator delete(void* p, std::size_t) noexcept { std::free(p); }
PROBELIGHTS_HIDDEN void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
PROBELIGHTS_HIDDEN void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
PROBELIGHTS_HIDDEN void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
PROBELIGHTS_HIDDEN void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
PROBELIGHTS_HIDDEN void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
PROBELIGHTS_HIDDEN void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
PROBELIGHTS_HIDDEN void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
PROBELIGHTS_HIDDEN void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept {
  std::free(p);
}
PROBELIGHTS_HIDDEN void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept {
  std::free(p);
}
