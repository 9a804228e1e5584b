# hfx_embed(TARGET <target> FUNCTION <c++ name> FILES <files...>)
# Turns text sources (GLSL, OpenCL C) into byte arrays compiled into <target>, reachable through
# `std::string_view <FUNCTION>(std::string_view fileName)`, so an installed library needs no source
# tree. Regenerated whenever a listed file changes.
set(HFX_EMBED_SCRIPT ${CMAKE_CURRENT_LIST_DIR}/HfxEmbedFiles.cmake)

function(hfx_embed)
    cmake_parse_arguments(ARG "" "TARGET;FUNCTION" "FILES" ${ARGN})
    set(out ${CMAKE_CURRENT_BINARY_DIR}/embedded_${ARG_FUNCTION}.cpp)
    add_custom_command(
        OUTPUT ${out}
        COMMAND ${CMAKE_COMMAND} -DOUT=${out} -DFUNCTION=${ARG_FUNCTION}
                "-DFILES=${ARG_FILES}" -P ${HFX_EMBED_SCRIPT}
        DEPENDS ${ARG_FILES} ${HFX_EMBED_SCRIPT}
        COMMENT "Embedding ${ARG_FUNCTION} sources"
        VERBATIM)
    target_sources(${ARG_TARGET} PRIVATE ${out})
endfunction()
