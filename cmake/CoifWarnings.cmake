# Off by default, so that a consumer building coif with another compiler is not stopped by a new warning; the
# project's own presets (CMakePresets.json) turn it on.
option(COIF_WERROR "Treat warnings as errors" OFF)
function(coif_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic $<$<BOOL:${COIF_WERROR}>:-Werror>)
endfunction()
