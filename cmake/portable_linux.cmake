# Links a Linux module so that it loads on glibc from 2.28 on (blender.org's floor, and the manylinux_2_28 wheel
# tag): libstdc++ and libgcc in, their symbols hidden, and the symbols of new glibc versions that they reference
# redirected to native/python/glibc_compat.cpp (why each: that file's header). libpthread.so.0 is named so that on
# glibc < 2.34 the old pthread versions resolve from it. Used by the add-on's modules and the Python package's.
function(probelights_link_portable_linux target)
  set(glibc_wraps "")
  foreach(symbol pthread_create pthread_join pthread_once pthread_detach __pthread_key_create pthread_key_create
                 pthread_key_delete pthread_getspecific pthread_setspecific __libc_single_threaded _dl_find_object
                 stat lstat fstat fstat64 exp log pow arc4random)
    list(APPEND glibc_wraps "-Wl,--wrap=${symbol}")
  endforeach()
  target_sources(${target} PRIVATE ${PROJECT_SOURCE_DIR}/native/python/glibc_compat.cpp)
  target_link_options(${target} PRIVATE -static-libstdc++ -static-libgcc -Wl,--exclude-libs,ALL -Wl,--as-needed
                      -Wl,--gc-sections ${glibc_wraps} "-Wl,--push-state,--no-as-needed" "-l:libpthread.so.0"
                      "-Wl,--pop-state")
endfunction()
