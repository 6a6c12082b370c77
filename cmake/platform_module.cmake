include(${CMAKE_CURRENT_LIST_DIR}/portable_linux.cmake)
# One portable module `target` of native/python/ (PROBELIGHTS_MODULE_SOURCES) over the portable core, for the
# CPython ABI `tag` (e.g. 311) whose headers are in `includes`, named `name` (that platform's extension suffix),
# linked for the platform being built (the add-on's modules, addon/CMakeLists.txt; the Python package's Windows
# and macOS ones, python/):
#   Linux    libstdc++ and libgcc in, glibc's new symbols redirected (glibc_compat.cpp), the rest of Python's API
#            left to the host Blender;
#   Windows  zig c++ (clang, libc++ and libunwind in, MinGW-w64's start-up code) against the UCRT, as Blender's
#            MSVC-built Python is; Python's API from python3XY.dll through an import library (scripts/cross-
#            toolchain.sh); -static keeps the C++ runtime out of the DLL list;
#   macOS    zig c++ (libc++ in), Python's API left to the host (-undefined dynamic_lookup, as every macOS extension
#            module); zig's linker signs it ad hoc, which arm64 Macs require of any code they load; operator
#            new and delete defined hidden (macos_operators.cpp), so it exports its init function alone.
function(probelights_platform_module target tag includes name output_dir)
  add_library(${target} MODULE ${PROBELIGHTS_MODULE_SOURCES})
  target_include_directories(${target} SYSTEM PRIVATE ${includes})
  target_link_libraries(${target} PRIVATE probelights_core_portable pybind11::headers)
  target_compile_definitions(${target} PRIVATE PROBELIGHTS_VERSION="${PROJECT_VERSION}")
  target_compile_options(${target} PRIVATE -ffunction-sections -fdata-sections)
  set_target_properties(${target} PROPERTIES PREFIX "" OUTPUT_NAME _probelights SUFFIX ${name}
                        CXX_VISIBILITY_PRESET hidden VISIBILITY_INLINES_HIDDEN ON
                        LIBRARY_OUTPUT_DIRECTORY ${output_dir})
  if(CMAKE_SYSTEM_NAME STREQUAL "Linux")
    probelights_link_portable_linux(${target})  # loads on glibc 2.28 on (cmake/portable_linux.cmake)
  elseif(CMAKE_SYSTEM_NAME STREQUAL "Windows")
    target_compile_definitions(${target} PRIVATE MS_WIN64)  # 3.11's PC/pyconfig.h sets it for MSVC alone
    target_link_libraries(${target} PRIVATE ${PROBELIGHTS_CROSS}/python/cp${tag}/libpython${tag}.a)
    target_link_options(${target} PRIVATE -static -s -Wl,--gc-sections)
  elseif(CMAKE_SYSTEM_NAME STREQUAL "Darwin")
    target_sources(${target} PRIVATE ${CMAKE_SOURCE_DIR}/native/python/macos_operators.cpp)
    set_source_files_properties(${CMAKE_SOURCE_DIR}/native/python/macos_operators.cpp PROPERTIES
                                COMPILE_OPTIONS -fvisibility-global-new-delete=force-hidden)
    target_link_options(${target} PRIVATE -undefined dynamic_lookup -Wl,-dead_strip
                        -Wl,-install_name,_probelights${name})
  endif()
endfunction()
