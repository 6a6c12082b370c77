# Builds the add-on's native modules for another platform with zig c++ (clang, libc++ linked in statically):
#   cmake -S . -B build/platforms/windows-x64 -DCMAKE_TOOLCHAIN_FILE=cmake/zig-toolchain.cmake \
#         -DPROBELIGHTS_PLATFORM=windows-x64 -DPROBELIGHTS_CROSS=$(scripts/cross-toolchain.sh)
# PROBELIGHTS_PLATFORM is a Blender extension platform: windows-x64, macos-arm64 or macos-x64. The main build does
# this for each platform in PROBELIGHTS_PLATFORMS (addon/CMakeLists.txt); only the portable core and its modules
# are built (CMAKE_CROSSCOMPILING).
list(APPEND CMAKE_TRY_COMPILE_PLATFORM_VARIABLES PROBELIGHTS_PLATFORM PROBELIGHTS_CROSS)
if(PROBELIGHTS_PLATFORM STREQUAL "windows-x64")
  set(CMAKE_SYSTEM_NAME Windows)
  set(CMAKE_SYSTEM_PROCESSOR AMD64)
  # The GNU ABI of clang with MinGW-w64's headers, linked against the UCRT as Blender's MSVC-built Python is.
  set(zig_target x86_64-windows-gnu)
elseif(PROBELIGHTS_PLATFORM STREQUAL "macos-arm64")
  set(CMAKE_SYSTEM_NAME Darwin)
  set(CMAKE_SYSTEM_PROCESSOR arm64)
  set(zig_target aarch64-macos.11.0)  # the oldest macOS that Blender 4.2-5.x run on is 11.2
elseif(PROBELIGHTS_PLATFORM STREQUAL "macos-x64")
  set(CMAKE_SYSTEM_NAME Darwin)
  set(CMAKE_SYSTEM_PROCESSOR x86_64)
  set(zig_target x86_64-macos.11.0)
else()
  message(FATAL_ERROR "PROBELIGHTS_PLATFORM '${PROBELIGHTS_PLATFORM}': use windows-x64, macos-arm64 or macos-x64")
endif()
if(NOT EXISTS "${PROBELIGHTS_CROSS}/bin/${zig_target}-c++")
  message(FATAL_ERROR "PROBELIGHTS_CROSS '${PROBELIGHTS_CROSS}' is not a toolchain of scripts/cross-toolchain.sh")
endif()
set(CMAKE_CXX_COMPILER "${PROBELIGHTS_CROSS}/bin/${zig_target}-c++")
set(CMAKE_C_COMPILER "${PROBELIGHTS_CROSS}/bin/${zig_target}-cc")
set(CMAKE_AR "${PROBELIGHTS_CROSS}/bin/zig-ar" CACHE FILEPATH "")
set(CMAKE_RANLIB "${PROBELIGHTS_CROSS}/bin/zig-ranlib" CACHE FILEPATH "")
# No SDK or Xcode here: zig carries the macOS headers and links against libSystem's stubs.
set(CMAKE_OSX_SYSROOT "" CACHE PATH "")
set(CMAKE_OSX_DEPLOYMENT_TARGET "" CACHE STRING "")
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
