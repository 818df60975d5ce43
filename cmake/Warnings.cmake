# Warnings as the project builds with them: gcc and clang, -Wall -Wextra,
# errors in CI (AMSPH_WERROR).
option(AMSPH_WERROR "Treat compiler warnings as errors" OFF)
function(amsph_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wshadow -Wstrict-prototypes
    $<$<BOOL:${AMSPH_WERROR}>:-Werror>)
endfunction()
