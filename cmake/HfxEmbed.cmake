# hfx_embed(TARGET <target> FUNCTION <c++ name> FILES <files...> [BASE <folder>])
# Turns text sources (GLSL, OpenCL C) into byte arrays compiled into <target>, reachable through
# `std::string_view <FUNCTION>(std::string_view fileName)`, so an installed library needs no source
# tree. Files are named by their path relative to BASE ("trace/pom.glsl"), or by their file name
# without it. Regenerated whenever a listed file changes.
set(HFX_EMBED_SCRIPT ${CMAKE_CURRENT_LIST_DIR}/HfxEmbedFiles.cmake)

function(hfx_embed)
    cmake_parse_arguments(ARG "" "TARGET;FUNCTION;BASE" "FILES" ${ARGN})
    set(out ${CMAKE_CURRENT_BINARY_DIR}/embedded_${ARG_FUNCTION}.cpp)
    add_custom_command(
        OUTPUT ${out}
        COMMAND ${CMAKE_COMMAND} -DOUT=${out} -DFUNCTION=${ARG_FUNCTION} -DBASE=${ARG_BASE}
                "-DFILES=${ARG_FILES}" -P ${HFX_EMBED_SCRIPT}
        DEPENDS ${ARG_FILES} ${HFX_EMBED_SCRIPT}
        COMMENT "Embedding ${ARG_FUNCTION} sources"
        VERBATIM)
    target_sources(${ARG_TARGET} PRIVATE ${out})
endfunction()
