# Warnings and sanitizers shared by every Corsa target. Call corsa_target_defaults(target).
add_library(corsa_build_flags INTERFACE)
target_compile_options(corsa_build_flags INTERFACE -Wall -Wextra -Wpedantic)
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
  # GCC 12 reports -Wrestrict inside libstdc++'s std::string operator+ at -O3, a known false
  # positive (GCC bug 105651, fixed in 13); likewise -Wstringop-overflow on std::string
  # concatenation with a temporary (GCC bug 105329), which depends on inlining decisions.
  target_compile_options(corsa_build_flags INTERFACE -Wno-restrict -Wno-stringop-overflow)
endif()
if(CMAKE_UNITY_BUILD AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  # A unity build compiles several .cpp files as one: GCC then treats every included .cpp as a
  # header and warns about its classes holding types from its own anonymous namespace, which is
  # right for a real header and meaningless here.
  target_compile_options(corsa_build_flags INTERFACE -Wno-subobject-linkage)
endif()
if(CORSA_WERROR)
  target_compile_options(corsa_build_flags INTERFACE -Werror)
endif()
if(CORSA_SANITIZE)
  target_compile_options(corsa_build_flags INTERFACE
    -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer)
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    # The sanitizer instrumentation defeats GCC's flow analysis: -Wmaybe-uninitialized then fires
    # inside libstdc++'s std::variant<..., std::string> move constructor (GCC bug 107919). The
    # Release build keeps the warning as an error.
    target_compile_options(corsa_build_flags INTERFACE -Wno-maybe-uninitialized)
  endif()
  target_link_options(corsa_build_flags INTERFACE -fsanitize=address,undefined)
endif()

function(corsa_target_defaults target)
  target_link_libraries(${target} PRIVATE corsa_build_flags)
endfunction()
