# Packs one platform's add-on zip, whole or not at all (written beside the zip, then renamed over it):
#   cmake -DSOURCE=addon/probe_lights -DMODULES="a.pyd|b.pyd" -DPLATFORM=windows-x64 -DSTAGE=dir -DZIP=out.zip \
#         -P addon/package.cmake
# The zip holds probe_lights/ with the add-on's .py and .json (measured data) files, its manifest with `platforms` set to PLATFORM alone
# (what Blender's `extension build --split-platforms` writes), and that platform's native modules.
foreach(var SOURCE MODULES PLATFORM STAGE ZIP)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "package.cmake: ${var} not given")
  endif()
endforeach()
string(REPLACE "|" ";" MODULES "${MODULES}")
list(LENGTH MODULES count)
if(count EQUAL 0)
  message(FATAL_ERROR "package.cmake: no modules for ${PLATFORM}")
endif()
file(REMOVE_RECURSE ${STAGE})
file(MAKE_DIRECTORY ${STAGE}/probe_lights)
file(GLOB sources ${SOURCE}/*.py ${SOURCE}/*.json)
file(COPY ${sources} ${MODULES} DESTINATION ${STAGE}/probe_lights)
file(READ ${SOURCE}/blender_manifest.toml manifest)
string(REGEX MATCH "\nplatforms = \\[[^]]*\\]" found "${manifest}")
if(NOT found)
  message(FATAL_ERROR "package.cmake: no 'platforms = [...]' line in ${SOURCE}/blender_manifest.toml")
endif()
string(REPLACE "${found}" "\nplatforms = [\"${PLATFORM}\"]" manifest "${manifest}")
file(WRITE ${STAGE}/probe_lights/blender_manifest.toml "${manifest}")
get_filename_component(name ${ZIP} NAME)
get_filename_component(folder ${ZIP} DIRECTORY)
set(partial ${folder}/.${name}.partial)
file(REMOVE ${partial})
execute_process(COMMAND ${CMAKE_COMMAND} -E tar cf ${partial} --format=zip probe_lights WORKING_DIRECTORY ${STAGE}
                COMMAND_ERROR_IS_FATAL ANY)
file(RENAME ${partial} ${ZIP})
