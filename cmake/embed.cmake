# raylane_embed_files(OUT_VAR OUTPUT_CPP FILE...): generates a C++ file that defines
# raylane::embedded_files(), a list of {file name, contents} for each FILE, so the built-in
# default scene needs nothing from the disk. Regenerated when a file changes.
function(raylane_embed_files out_var output)
  set(script ${PROJECT_SOURCE_DIR}/cmake/embed_run.cmake)
  string(REPLACE ";" "|" files "${ARGN}")
  add_custom_command(
    OUTPUT ${output}
    COMMAND ${CMAKE_COMMAND} -DOUTPUT=${output} "-DFILES=${files}" -P ${script}
    DEPENDS ${ARGN} ${script}
    COMMENT "Embedding the built-in scene"
    VERBATIM)
  set(${out_var} ${output} PARENT_SCOPE)
endfunction()
