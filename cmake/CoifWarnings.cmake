option(COIF_WERROR "Treat warnings as errors" ON)
function(coif_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic $<$<BOOL:${COIF_WERROR}>:-Werror>)
endfunction()
