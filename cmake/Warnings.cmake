# Project-wide warning flags, applied per target with scanpick_set_warnings(<target>).
function(scanpick_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow=local -Wnon-virtual-dtor
                                           -Wno-deprecated-declarations)
  if(SCANPICK_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
