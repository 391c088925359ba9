# coif_embed(<target> FUNCTION <name> BASE <dir> FILES <files...>)
# Compiles the files into <target> as byte arrays and defines
#   std::optional<std::span<const unsigned char>> coif::embedded::<name>(std::string_view path)
# where path is the file's path relative to BASE (e.g. "shaders/envmap.glsl"). Rebuilt when a file changes.
set(COIF_EMBED_SCRIPT ${CMAKE_CURRENT_LIST_DIR}/embed_files.cmake)
function(coif_embed target)
  cmake_parse_arguments(ARG "" "FUNCTION;BASE" "FILES" ${ARGN})
  set(out ${PROJECT_BINARY_DIR}/generated/embedded_${ARG_FUNCTION}.cpp)
  set(list_file ${PROJECT_BINARY_DIR}/generated/embedded_${ARG_FUNCTION}.txt)
  set(rel)
  foreach(f IN LISTS ARG_FILES)
    file(RELATIVE_PATH r ${ARG_BASE} ${f})
    list(APPEND rel ${r})
  endforeach()
  string(REPLACE ";" "\n" rel_lines "${rel}")
  file(GENERATE OUTPUT ${list_file} CONTENT "${rel_lines}\n")
  add_custom_command(OUTPUT ${out}
    COMMAND ${CMAKE_COMMAND} -DBASE=${ARG_BASE} -DLIST=${list_file} -DOUT=${out} -DFUNCTION=${ARG_FUNCTION}
            -P ${COIF_EMBED_SCRIPT}
    DEPENDS ${ARG_FILES} ${COIF_EMBED_SCRIPT} ${list_file}
    COMMENT "Embedding ${ARG_FUNCTION} files" VERBATIM)
  target_sources(${target} PRIVATE ${out})
endfunction()
