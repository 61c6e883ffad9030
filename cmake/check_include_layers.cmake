# Checks that the subfolders of a source folder include each other one way only, in a declared
# order of layers. Run as a script:
#
#   cmake -DROOT=<folder> "-DLAYERS=<bottom> <next> ... <top>" -P check_include_layers.cmake
#
# LAYERS lists the subfolders of ROOT from the bottom layer up; peers share a layer, joined by
# "|" (e.g. "conditions|actions"): neither may include the other. A file in layer L may include
# "<folder>/..." only for a folder of a layer below L, or its own folder.
# Includes whose first path part is not a declared layer (e.g. "corsa/engine/...", system
# headers) are not checked. Also errors: an include through "../", a subfolder of ROOT that
# LAYERS does not place, and a source file directly in ROOT (every source belongs to a layer).
# Every violation is printed as `file:line: error: ...`; any violation fails the script.

cmake_minimum_required(VERSION 3.25)

if(NOT DEFINED ROOT OR NOT DEFINED LAYERS)
  message(FATAL_ERROR "usage: cmake -DROOT=<folder> \"-DLAYERS=<bottom> ... <top>\" -P ${CMAKE_CURRENT_LIST_FILE}")
endif()
if(NOT IS_DIRECTORY "${ROOT}")
  message(FATAL_ERROR "${ROOT}: not a folder")
endif()

# Rank of each folder: its layer's position, bottom 0.
separate_arguments(layer_list UNIX_COMMAND "${LAYERS}")
set(rank 0)
set(folders "")
foreach(layer IN LISTS layer_list)
  string(REPLACE "|" ";" peers "${layer}")
  foreach(folder IN LISTS peers)
    if(folder IN_LIST folders)
      message(FATAL_ERROR "LAYERS names '${folder}' twice")
    endif()
    list(APPEND folders "${folder}")
    set(rank_of_${folder} ${rank})
  endforeach()
  math(EXPR rank "${rank} + 1")
endforeach()
string(REPLACE ";" " -> " order_text "${LAYERS}")
string(REPLACE " " " -> " order_text "${order_text}")

set(errors 0)
macro(report file line text)
  message("${file}:${line}: error: ${text}")
  math(EXPR errors "${errors} + 1")
endmacro()

# Every subfolder is placed; no source file sits outside the layers.
file(GLOB entries LIST_DIRECTORIES true RELATIVE "${ROOT}" "${ROOT}/*")
list(SORT entries)
foreach(entry IN LISTS entries)
  if(IS_DIRECTORY "${ROOT}/${entry}")
    if(NOT entry IN_LIST folders)
      report("${ROOT}/${entry}" 1 "folder '${entry}' is in no layer (add it to the order: ${order_text})")
    endif()
  elseif(entry MATCHES "\\.(h|hpp|c|cc|cpp|in)$")
    report("${ROOT}/${entry}" 1 "source file outside every layer folder (order: ${order_text})")
  endif()
endforeach()

foreach(folder IN LISTS folders)
  if(NOT IS_DIRECTORY "${ROOT}/${folder}")
    message(FATAL_ERROR "LAYERS names '${folder}', which is not a folder of ${ROOT}")
  endif()
  file(GLOB_RECURSE sources LIST_DIRECTORIES false "${ROOT}/${folder}/*")
  list(SORT sources)
  foreach(source IN LISTS sources)
    if(NOT source MATCHES "\\.(h|hpp|c|cc|cpp|in)$")
      continue()
    endif()
    # One list element per line: characters that CMake lists treat specially (; [ ] \) are
    # replaced first, so that line numbers stay right.
    file(READ "${source}" content)
    string(REPLACE "\\" "/" content "${content}")
    string(REPLACE ";" "," content "${content}")
    string(REPLACE "[" "(" content "${content}")
    string(REPLACE "]" ")" content "${content}")
    string(REPLACE "\n" ";" lines "${content}")
    set(line_number 0)
    foreach(line IN LISTS lines)
      math(EXPR line_number "${line_number} + 1")
      if(line MATCHES "^[ \t]*#[ \t]*include[ \t]*\"\\.\\./")
        report("${source}" ${line_number} "include through '../' (name the layer folder instead)")
        continue()
      endif()
      if(NOT line MATCHES "^[ \t]*#[ \t]*include[ \t]*\"([A-Za-z0-9_.-]+)/[^\"]*\"")
        continue()
      endif()
      set(target "${CMAKE_MATCH_1}")
      if(target STREQUAL folder OR NOT DEFINED rank_of_${target})
        continue()
      endif()
      if(NOT rank_of_${target} LESS rank_of_${folder})
        if(rank_of_${target} EQUAL rank_of_${folder})
          set(where "a peer of the same layer")
        else()
          set(where "a layer above it")
        endif()
        report("${source}" ${line_number}
               "'${folder}/' includes '${target}/', ${where} (order, bottom to top: ${order_text})")
      endif()
    endforeach()
  endforeach()
endforeach()

if(errors GREATER 0)
  message(FATAL_ERROR "${errors} include layer violation(s) under ${ROOT}")
endif()
message(STATUS "include layers ok under ${ROOT}: ${order_text}")
