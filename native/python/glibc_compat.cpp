// Linked only into the Blender add-on's portable modules (addon/CMakeLists.txt): keeps them loadable on glibc
// older than the one they are built against (Debian 12: 2.36), down to what blender.org's Blender needs
// (2.28).
//
// The statically linked libstdc++ and libgcc reference four symbols that only new glibc versions define. The
// link redirects them here (-Wl,--wrap=NAME turns every reference to NAME into __wrap_NAME):
//   pthread_create, pthread_join, pthread_once, __pthread_key_create
//                           @GLIBC_2.34 (libpthread moved into libc)
//       -> the same functions at their original version GLIBC_2.2.5, which every glibc since 2002 exports (in
//          libpthread.so.0 before 2.34, which the module also names as NEEDED; in libc.so.6 after);
//   __libc_single_threaded  @GLIBC_2.32 (libstdc++ skips atomic reference counts while the process has one
//                           thread)
//       -> a constant 0: "maybe multi-threaded", always the atomic path, correct in any process;
//   _dl_find_object         @GLIBC_2.35 (libgcc's unwinder finds the .eh_frame_hdr of the object holding a
//                           return address)
//       -> the same answer found with dl_iterate_phdr (GLIBC_2.2.5), the way libgcc did before glibc had it.
// tests/python/test_portable_module.py checks the versions the modules need and that exceptions still unwind.
#include <dlfcn.h>
#include <link.h>
#include <pthread.h>

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

__attribute__((visibility("hidden"))) char __wrap___libc_single_threaded = 0;

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
