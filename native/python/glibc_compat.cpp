// Linked into the portable modules (cmake/portable_linux.cmake: the Blender add-on's, addon/CMakeLists.txt,
// and the Python package's, python/CMakeLists.txt): keeps them loadable on glibc older than the one they are
// built against (Debian 12: 2.36), down to what blender.org's Blender and the manylinux_2_28 tag need (2.28).
//
// The statically linked libstdc++ and libgcc, and our code, reference symbols that only new glibc versions
// define. The link redirects them here (-Wl,--wrap=NAME turns every reference to NAME into __wrap_NAME):
//   pthread_create, pthread_join, pthread_once, pthread_detach, __pthread_key_create, pthread_key_create,
//   pthread_key_delete, pthread_getspecific, pthread_setspecific
//                           @GLIBC_2.34 (libpthread moved into libc)
//       -> the same functions at their original version GLIBC_2.2.5, which every glibc since 2002 exports (in
//          libpthread.so.0 before 2.34, which the module also names as NEEDED; in libc.so.6 after);
//   __libc_single_threaded  @GLIBC_2.32 (libstdc++ skips atomic reference counts while the process has one
//                           thread)
//       -> a constant 0: "maybe multi-threaded", always the atomic path, correct in any process;
//   _dl_find_object         @GLIBC_2.35 (libgcc's unwinder finds the .eh_frame_hdr of the object holding a
//                           return address)
//       -> the same answer found with dl_iterate_phdr (GLIBC_2.2.5), the way libgcc did before glibc had it;
//   stat, lstat, fstat, fstat64
//                           @GLIBC_2.33 (before, <sys/stat.h> inlined them as calls of __xstat and kin)
//       -> __xstat, __lxstat, __fxstat, __fxstat64 (GLIBC_2.2.5, still exported by new glibc) with
//          _STAT_VER 1, x86-64's, as those inlines passed it (struct stat and stat64 are one layout there);
//   exp, log, pow           @GLIBC_2.29 (the same functions without the SVID error wrapper)
//       -> the GLIBC_2.2.5 versions: the same code (glibc 2.28 brought it) behind a wrapper that only sets
//          errno on overflow, so every finite result is the same bits;
//   arc4random              @GLIBC_2.36 (libstdc++'s std::random_device)
//       -> 32 bits from the getrandom system call, the kernel's generator that arc4random reads too.
// tests/python/test_portable_module.py checks the versions the modules need and that exceptions still unwind;
// tests/package/test_package.py that the wheel's tag is manylinux_2_28.
#include <dlfcn.h>
#include <fcntl.h>
#include <link.h>
#include <pthread.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>

extern "C" {

int probelights_pthread_create(pthread_t*, const pthread_attr_t*, void* (*)(void*), void*);
int probelights_pthread_join(pthread_t, void**);
int probelights_pthread_once(pthread_once_t*, void (*)());
int probelights_pthread_key_create(pthread_key_t*, void (*)(void*));
__asm__(".symver probelights_pthread_create,pthread_create@GLIBC_2.2.5");
__asm__(".symver probelights_pthread_join,pthread_join@GLIBC_2.2.5");
__asm__(".symver probelights_pthread_once,pthread_once@GLIBC_2.2.5");
__asm__(".symver probelights_pthread_key_create,__pthread_key_create@GLIBC_2.2.5");

__attribute__((visibility("hidden"))) int __wrap_pthread_create(pthread_t* thread, const pthread_attr_t* attr,
                                                                void* (*start)(void*), void* arg) {
  return probelights_pthread_create(thread, attr, start, arg);
}
__attribute__((visibility("hidden"))) int __wrap_pthread_join(pthread_t thread, void** result) {
  return probelights_pthread_join(thread, result);
}
__attribute__((visibility("hidden"))) int __wrap_pthread_once(pthread_once_t* once, void (*init)()) {
  return probelights_pthread_once(once, init);
}
__attribute__((visibility("hidden"))) int __wrap___pthread_key_create(pthread_key_t* key,
                                                                      void (*destructor)(void*)) {
  return probelights_pthread_key_create(key, destructor);
}

int probelights_pthread_detach(pthread_t);
int probelights_pthread_key_create2(pthread_key_t*, void (*)(void*));
int probelights_pthread_key_delete(pthread_key_t);
void* probelights_pthread_getspecific(pthread_key_t);
int probelights_pthread_setspecific(pthread_key_t, const void*);
__asm__(".symver probelights_pthread_detach,pthread_detach@GLIBC_2.2.5");
__asm__(".symver probelights_pthread_key_create2,pthread_key_create@GLIBC_2.2.5");
__asm__(".symver probelights_pthread_key_delete,pthread_key_delete@GLIBC_2.2.5");
__asm__(".symver probelights_pthread_getspecific,pthread_getspecific@GLIBC_2.2.5");
__asm__(".symver probelights_pthread_setspecific,pthread_setspecific@GLIBC_2.2.5");

__attribute__((visibility("hidden"))) int __wrap_pthread_detach(pthread_t thread) {
  return probelights_pthread_detach(thread);
}
__attribute__((visibility("hidden"))) int __wrap_pthread_key_create(pthread_key_t* key,
                                                                    void (*destructor)(void*)) {
  return probelights_pthread_key_create2(key, destructor);
}
__attribute__((visibility("hidden"))) int __wrap_pthread_key_delete(pthread_key_t key) {
  return probelights_pthread_key_delete(key);
}
__attribute__((visibility("hidden"))) void* __wrap_pthread_getspecific(pthread_key_t key) {
  return probelights_pthread_getspecific(key);
}
__attribute__((visibility("hidden"))) int __wrap_pthread_setspecific(pthread_key_t key, const void* value) {
  return probelights_pthread_setspecific(key, value);
}

__attribute__((visibility("hidden"))) char __wrap___libc_single_threaded = 0;

// The stat family through the pre-2.33 entry points (_STAT_VER 1 on x86-64).
int probelights_xstat(int, const char*, struct stat*);
int probelights_lxstat(int, const char*, struct stat*);
int probelights_fxstat(int, int, struct stat*);
int probelights_fxstat64(int, int, struct stat64*);
__asm__(".symver probelights_xstat,__xstat@GLIBC_2.2.5");
__asm__(".symver probelights_lxstat,__lxstat@GLIBC_2.2.5");
__asm__(".symver probelights_fxstat,__fxstat@GLIBC_2.2.5");
__asm__(".symver probelights_fxstat64,__fxstat64@GLIBC_2.2.5");
constexpr int kStatVersion = 1;

__attribute__((visibility("hidden"))) int __wrap_stat(const char* path, struct stat* buf) {
  return probelights_xstat(kStatVersion, path, buf);
}
__attribute__((visibility("hidden"))) int __wrap_lstat(const char* path, struct stat* buf) {
  return probelights_lxstat(kStatVersion, path, buf);
}
__attribute__((visibility("hidden"))) int __wrap_fstat(int fd, struct stat* buf) {
  return probelights_fxstat(kStatVersion, fd, buf);
}
__attribute__((visibility("hidden"))) int __wrap_fstat64(int fd, struct stat64* buf) {
  return probelights_fxstat64(kStatVersion, fd, buf);
}

double probelights_exp(double);
double probelights_log(double);
double probelights_pow(double, double);
__asm__(".symver probelights_exp,exp@GLIBC_2.2.5");
__asm__(".symver probelights_log,log@GLIBC_2.2.5");
__asm__(".symver probelights_pow,pow@GLIBC_2.2.5");

__attribute__((visibility("hidden"))) double __wrap_exp(double x) { return probelights_exp(x); }
__attribute__((visibility("hidden"))) double __wrap_log(double x) { return probelights_log(x); }
__attribute__((visibility("hidden"))) double __wrap_pow(double x, double y) { return probelights_pow(x, y); }

__attribute__((visibility("hidden"))) std::uint32_t __wrap_arc4random() {
  std::uint32_t value = 0;
  for (;;) {
    const long n = syscall(SYS_getrandom, &value, sizeof value, 0);
    if (n == static_cast<long>(sizeof value)) return value;
    if (n < 0 && errno != EINTR) break;  // a kernel before 3.17 has no getrandom: its device then
  }
  const int fd = open("/dev/urandom", O_RDONLY | O_CLOEXEC);
  if (fd >= 0) {
    if (read(fd, &value, sizeof value) != static_cast<ssize_t>(sizeof value)) value = 0;
    close(fd);
  }
  return value;
}

namespace {
struct Search {
  std::uintptr_t address;
  dl_find_object* result;
  bool found;
};

// For the loaded object whose PT_LOAD segment holds the address: its mapping and its PT_GNU_EH_FRAME segment.
int findObject(dl_phdr_info* info, std::size_t, void* data) {
  auto* search = static_cast<Search*>(data);
  const ElfW(Phdr)* ehFrame = nullptr;
  std::uintptr_t start = UINTPTR_MAX, end = 0;
  bool holds = false;
  for (int i = 0; i < info->dlpi_phnum; ++i) {
    const ElfW(Phdr)& p = info->dlpi_phdr[i];
    if (p.p_type == PT_LOAD) {
      const std::uintptr_t s = info->dlpi_addr + p.p_vaddr, e = s + p.p_memsz;
      if (s < start) start = s;
      if (e > end) end = e;
      if (search->address >= s && search->address < e) holds = true;
    } else if (p.p_type == PT_GNU_EH_FRAME) {
      ehFrame = &p;
    }
  }
  if (!holds) return 0;
  *search->result = dl_find_object{};
  search->result->dlfo_map_start = reinterpret_cast<void*>(start);
  search->result->dlfo_map_end = reinterpret_cast<void*>(end);
  search->result->dlfo_eh_frame =
      ehFrame ? reinterpret_cast<void*>(info->dlpi_addr + ehFrame->p_vaddr) : nullptr;
  search->found = true;
  return 1;
}
}  // namespace

__attribute__((visibility("hidden"))) int __wrap__dl_find_object(void* address, dl_find_object* result) {
  Search search{reinterpret_cast<std::uintptr_t>(address), result, false};
  dl_iterate_phdr(findObject, &search);
  return search.found ? 0 : -1;
}

}  // extern "C"
