# tacta_set_warnings(target): the project's warning set, on every target it builds (installed
# with the package, so out-of-tree plugins get the same set; -Werror only with
# TACTA_WARNINGS_AS_ERRORS).
include_guard(GLOBAL)

function(tacta_set_warnings target)
  target_compile_options(${target} PRIVATE
    $<$<COMPILE_LANGUAGE:CXX>:-Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wold-style-cast
      -Wcast-align -Woverloaded-virtual -Wdouble-promotion -Wformat=2
      -Wimplicit-fallthrough>
    $<$<COMPILE_LANGUAGE:C>:-Wall -Wextra -Wpedantic>)
  if(TACTA_WARNINGS_AS_ERRORS)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
