# One place for warning flags; applied PRIVATE so consumers are not affected.
function(gridloc_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow)
endfunction()
