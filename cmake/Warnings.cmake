# Project-wide warning flags, applied per target with scanpick_set_warnings(<target>).
function(scanpick_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wnon-virtual-dtor
                                           -Wno-deprecated-declarations)
  # GCC's -Wshadow=local; clang (the fuzz build) has no such level.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    target_compile_options(${target} PRIVATE -Wshadow=local)
  endif()
  if(SCANPICK_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
