# Embeds GLSL files into a generated C++ source as raw string literals, so the binaries carry
# their shaders and never look for files at run time.
function(sublift_embed_shaders out_var)
  set(gen "${CMAKE_CURRENT_BINARY_DIR}/embedded_shaders.cpp")
  set(srcs ${ARGN})
  add_custom_command(
    OUTPUT "${gen}"
    COMMAND ${CMAKE_COMMAND} -DOUT=${gen} "-DSRCS=${srcs}" -P "${PROJECT_SOURCE_DIR}/cmake/embed_shaders_run.cmake"
    DEPENDS ${srcs} "${PROJECT_SOURCE_DIR}/cmake/embed_shaders_run.cmake"
    COMMENT "Embedding shaders"
    VERBATIM)
  set(${out_var} "${gen}" PARENT_SCOPE)
endfunction()
