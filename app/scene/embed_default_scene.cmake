# Compiles the built-in default scene (assets/scenes/default.json) into the binary.
#
# Generates a .cpp defining
#     const char* weft_default_scene_json();
# which returns the JSON text verbatim, held in a raw string literal. The .cpp is regenerated
# whenever the JSON (or this file) changes.
#
# Hook it into app/CMakeLists.txt:
#
#     include(${CMAKE_CURRENT_SOURCE_DIR}/embed_default_scene.cmake)
#     weft_embed_default_scene(
#       JSON   ${PROJECT_SOURCE_DIR}/assets/scenes/default.json
#       OUTPUT ${CMAKE_CURRENT_BINARY_DIR}/default_scene_json.cpp)
#     add_library(weft_app_core
#       units.cpp json_reader.cpp scene.cpp
#       ${CMAKE_CURRENT_BINARY_DIR}/default_scene_json.cpp)
#     target_include_directories(weft_app_core PUBLIC ${PROJECT_SOURCE_DIR})
#     target_link_libraries(weft_app_core
#       PUBLIC weft_sim weft_render nlohmann_json::nlohmann_json PRIVATE weft_warnings)
#
# The function adds a custom command producing OUTPUT; listing OUTPUT among a target's sources
# (same directory) is what makes it run. This file is also the script the command runs:
#     cmake -DINPUT=<json> -DOUTPUT=<cpp> -P embed_default_scene.cmake

if(CMAKE_SCRIPT_MODE_FILE)
  # Script mode: write OUTPUT from INPUT.
  if(NOT INPUT OR NOT OUTPUT)
    message(FATAL_ERROR "embed_default_scene.cmake: pass -DINPUT=<json> -DOUTPUT=<cpp>")
  endif()
  file(READ "${INPUT}" weft_json)
  set(weft_delimiter "weft_scene_json")
  string(FIND "${weft_json}" ")${weft_delimiter}\"" weft_clash)
  if(NOT weft_clash EQUAL -1)
    message(FATAL_ERROR "${INPUT} contains ')${weft_delimiter}\"', the raw string's delimiter")
  endif()
  set(weft_cpp "// Generated from ${INPUT} by app/embed_default_scene.cmake. Do not edit.\n\n")
  string(APPEND weft_cpp "const char* weft_default_scene_json();\n\n")
  string(APPEND weft_cpp "const char* weft_default_scene_json() {\n")
  string(APPEND weft_cpp "  return R\"${weft_delimiter}(${weft_json})${weft_delimiter}\";\n")
  string(APPEND weft_cpp "}\n")
  file(WRITE "${OUTPUT}" "${weft_cpp}")
  return()
endif()

# weft_embed_default_scene(JSON <scene.json> OUTPUT <generated.cpp>)
function(weft_embed_default_scene)
  cmake_parse_arguments(ARG "" "JSON;OUTPUT" "" ${ARGN})
  if(NOT ARG_JSON OR NOT ARG_OUTPUT)
    message(FATAL_ERROR "weft_embed_default_scene: JSON and OUTPUT are required")
  endif()
  add_custom_command(
    OUTPUT ${ARG_OUTPUT}
    COMMAND ${CMAKE_COMMAND} -DINPUT=${ARG_JSON} -DOUTPUT=${ARG_OUTPUT}
            -P ${CMAKE_CURRENT_FUNCTION_LIST_FILE}
    DEPENDS ${ARG_JSON} ${CMAKE_CURRENT_FUNCTION_LIST_FILE}
    COMMENT "Embedding the default scene ${ARG_JSON}"
    VERBATIM)
endfunction()
