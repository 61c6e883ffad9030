# Shows that cmake/check_include_layers.cmake catches what it is for, on a copy of the engine's
# sources (the tree itself is never touched):
#   1. the unchanged copy passes;
#   2. an include of the top layer planted in a file of the bottom layer fails, named at its
#      file and line;
#   3. two peers of one layer including each other fail;
#   4. a new folder that the order does not place fails.
#
#   cmake -DCHECKER=<check_include_layers.cmake> -DROOT=<src> "-DLAYERS=..." -DWORK=<scratch>
#         -P include_layers_self_test.cmake

cmake_minimum_required(VERSION 3.25)

separate_arguments(layer_list UNIX_COMMAND "${LAYERS}")
list(GET layer_list 0 bottom_layer)
list(GET layer_list -1 top_layer)
string(REPLACE "|" ";" bottom_peers "${bottom_layer}")
string(REPLACE "|" ";" top_peers "${top_layer}")
list(GET bottom_peers 0 bottom)
list(GET top_peers 0 top)

# The first layer with peers, for case 3.
set(peer_a "")
foreach(layer IN LISTS layer_list)
  if(layer MATCHES "^([^|]+)\\|([^|]+)")
    set(peer_a "${CMAKE_MATCH_1}")
    set(peer_b "${CMAKE_MATCH_2}")
    break()
  endif()
endforeach()

function(fresh_copy)
  file(REMOVE_RECURSE "${WORK}")
  file(MAKE_DIRECTORY "${WORK}")
  file(COPY "${ROOT}/" DESTINATION "${WORK}")
endfunction()

# Runs the checker on the copy; sets `code` and `output` in the caller.
macro(run_checker)
  execute_process(COMMAND "${CMAKE_COMMAND}" "-DROOT=${WORK}" "-DLAYERS=${LAYERS}" -P "${CHECKER}"
                  RESULT_VARIABLE code OUTPUT_VARIABLE output ERROR_VARIABLE output)
endmacro()

# Appends `text` to the first header of `folder` in the copy; sets `planted` to its path and
# `planted_line` to the line the text lands on.
function(plant folder text)
  file(GLOB headers "${WORK}/${folder}/*.h")
  list(SORT headers)
  list(GET headers 0 file)
  file(READ "${file}" content)
  string(REGEX MATCHALL "\n" newlines "${content}")
  list(LENGTH newlines count)
  if(NOT content MATCHES "\n$")
    file(APPEND "${file}" "\n")
    math(EXPR count "${count} + 1")
  endif()
  file(APPEND "${file}" "${text}\n")
  math(EXPR line "${count} + 1")
  set(planted "${file}" PARENT_SCOPE)
  set(planted_line "${line}" PARENT_SCOPE)
endfunction()

# `text` with the characters that mean something in a CMake regex escaped.
function(regex_escape text out)
  string(REGEX REPLACE "([][.*+?^$()|\\])" "\\\\\\1" escaped "${text}")
  set(${out} "${escaped}" PARENT_SCOPE)
endfunction()

function(expect_failure what pattern)
  if(code EQUAL 0)
    message(FATAL_ERROR "${what}: the checker passed, it should have failed:\n${output}")
  endif()
  if(NOT output MATCHES "${pattern}")
    message(FATAL_ERROR "${what}: the checker failed without saying '${pattern}':\n${output}")
  endif()
  message(STATUS "${what}: caught")
endfunction()

# 1. The copy as it is.
fresh_copy()
run_checker()
if(NOT code EQUAL 0)
  message(FATAL_ERROR "the unchanged copy fails the checker:\n${output}")
endif()
message(STATUS "unchanged copy: passes")

# 2. The bottom layer including the top one.
plant("${bottom}" "#include \"${top}/planted.h\"")
regex_escape("${planted}" planted)
run_checker()
expect_failure("'${bottom}/' including '${top}/'"
               "${planted}:${planted_line}: error: '${bottom}/' includes '${top}/', a layer above it")

# 3. Peers including each other.
if(peer_a)
  fresh_copy()
  plant("${peer_a}" "#include \"${peer_b}/planted.h\"")
  regex_escape("${planted}" planted)
  run_checker()
  expect_failure("peers '${peer_a}/' including '${peer_b}/'"
                 "${planted}:${planted_line}: error: '${peer_a}/' includes '${peer_b}/', a peer")
endif()

# 4. A folder outside the order.
fresh_copy()
file(MAKE_DIRECTORY "${WORK}/unplaced")
run_checker()
expect_failure("an unplaced folder" "folder 'unplaced' is in no layer")

file(REMOVE_RECURSE "${WORK}")
