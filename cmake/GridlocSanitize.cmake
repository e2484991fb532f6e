# GRIDLOC_SANITIZE: sanitizers for every target of this build (cmake/sanitize.sh runs them).
#   -DGRIDLOC_SANITIZE=address,undefined   AddressSanitizer + UndefinedBehaviorSanitizer
#   -DGRIDLOC_SANITIZE=thread              ThreadSanitizer
# Empty (the default) adds nothing. A sanitizer build also defines GRIDLOC_NO_CLONES, which
# turns off target_clones multi-versioning: its ifunc resolver runs while the dynamic loader
# relocates, before ThreadSanitizer's runtime is ready, and crashes the process at start-up.
# The clone-free path is the "default" clone; the run-time dispatched kernels
# (fixed_point_kernel.cpp) are plain function pointers and stay on.
set(GRIDLOC_SANITIZE "" CACHE STRING
    "Sanitizers for every target: empty (none), address,undefined, or thread")

function(gridloc_check_sanitize value)
  string(REPLACE "," ";" names "${value}")
  foreach(name IN LISTS names)
    if(NOT name MATCHES "^(address|undefined|thread)$")
      message(FATAL_ERROR "GRIDLOC_SANITIZE: unknown sanitizer '${name}' in '${value}' "
                          "(use address,undefined or thread)")
    endif()
  endforeach()
  if("thread" IN_LIST names AND "address" IN_LIST names)
    message(FATAL_ERROR "GRIDLOC_SANITIZE: thread and address cannot be combined ('${value}')")
  endif()
endfunction()

if(GRIDLOC_SANITIZE)
  gridloc_check_sanitize("${GRIDLOC_SANITIZE}")
  message(STATUS "gridloc: sanitizers ${GRIDLOC_SANITIZE}, target_clones off")
  add_compile_options(-fsanitize=${GRIDLOC_SANITIZE} -fno-omit-frame-pointer
                      -fno-sanitize-recover=all)
  add_link_options(-fsanitize=${GRIDLOC_SANITIZE})
  add_compile_definitions(GRIDLOC_NO_CLONES)
endif()
