# The instrumented builds (WEFT_SANITIZE, WEFT_FUZZ; docs/reliability.md) instrument the code that
# reads hostile input, base/ and app/ (scene files, units, JSON, the command line), and with
# WEFT_PREBUILT_DIR set they take the simulator, analysis, renderer and chart libraries from a
# Release build of the same tree instead of compiling them again: each of those targets keeps its
# include folders, definitions and link dependencies (so nothing here repeats them), but its
# sources are replaced by an empty file and the Release build's archive is put first on its link
# interface. That build must be up to date (scripts/test-sanitized runs scripts/setup first); a
# program relinks when an archive changes. AddressSanitizer needs only the program itself linked
# with -fsanitize=address: calls into uninstrumented code are not checked, not misreported.
set(WEFT_PREBUILT_LIBRARIES weft_sim weft_analysis weft_render weft_chart)
if(TARGET weft_remesh)  # the remesher (CGAL): 50 s of the instrumented build's compile time alone
  list(APPEND WEFT_PREBUILT_LIBRARIES weft_remesh)
endif()

# Checks that `dir` is a build of this tree with the same optional parts, then swaps in its
# archives. Call after every library target is defined.
function(weft_use_prebuilt_libraries dir)
  get_filename_component(dir "${dir}" ABSOLUTE BASE_DIR "${CMAKE_BINARY_DIR}")
  if(NOT EXISTS "${dir}/CMakeCache.txt")
    message(FATAL_ERROR "WEFT_PREBUILT_DIR=${dir}: not a CMake build folder (build it first: scripts/setup)")
  endif()
  set(options WEFT_WITH_OSMESA WEFT_WITH_EGL WEFT_WITH_EMBREE_RT WEFT_WITH_CHOLMOD)
  load_cache("${dir}" READ_WITH_PREFIX prebuilt_ CMAKE_HOME_DIRECTORY CMAKE_BUILD_TYPE ${options})
  get_filename_component(prebuilt_source "${prebuilt_CMAKE_HOME_DIRECTORY}" REALPATH)
  get_filename_component(own_source "${PROJECT_SOURCE_DIR}" REALPATH)
  if(NOT prebuilt_source STREQUAL own_source)
    message(FATAL_ERROR "WEFT_PREBUILT_DIR=${dir} builds ${prebuilt_source}, not ${own_source}")
  endif()
  if(NOT prebuilt_CMAKE_BUILD_TYPE STREQUAL "Release")
    message(FATAL_ERROR "WEFT_PREBUILT_DIR=${dir}: expected a Release build, got '${prebuilt_CMAKE_BUILD_TYPE}'")
  endif()
  foreach(option ${options})
    if(NOT "${prebuilt_${option}}" STREQUAL "${${option}}")
      message(FATAL_ERROR "WEFT_PREBUILT_DIR=${dir} has ${option}=${prebuilt_${option}}, this build "
                          "${${option}}: configure both alike")
    endif()
  endforeach()

  set(placeholder "${CMAKE_BINARY_DIR}/prebuilt_placeholder.cpp")
  file(WRITE "${placeholder}" "// Empty: the library's code is the archive of WEFT_PREBUILT_DIR.\n")
  foreach(target ${WEFT_PREBUILT_LIBRARIES})
    get_target_property(binary_dir ${target} BINARY_DIR)
    file(RELATIVE_PATH folder "${PROJECT_BINARY_DIR}" "${binary_dir}")
    set(archive "${dir}/${folder}/${CMAKE_STATIC_LIBRARY_PREFIX}${target}${CMAKE_STATIC_LIBRARY_SUFFIX}")
    if(NOT EXISTS "${archive}")
      message(FATAL_ERROR "WEFT_PREBUILT_DIR: ${archive} is missing (build ${dir} first: scripts/setup)")
    endif()
    get_target_property(interface ${target} INTERFACE_LINK_LIBRARIES)
    if(NOT interface)
      set(interface "")
    endif()
    set_property(TARGET ${target} PROPERTY SOURCES "${placeholder}")
    set_property(TARGET ${target} PROPERTY INTERFACE_LINK_LIBRARIES "${archive}" ${interface})
  endforeach()
  message(STATUS "Instrumented base/ and app/; ${WEFT_PREBUILT_LIBRARIES} from ${dir}")
endfunction()
