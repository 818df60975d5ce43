# amsph_embed_kernels(<target> <kernel files...>)
# Builds cmake/embed_kernels.c, runs it over kernels/, and adds to <target>:
#   - amsph_kernel_source.c: the flattened OpenCL source (runs from any directory)
#   - the OpenMP kernel tables, the same files compiled as C11 once per
#     (dimension, smoothing kernel).
function(amsph_embed_kernels target)
  set(kernel_dir ${PROJECT_SOURCE_DIR}/kernels)
  set(source_c ${CMAKE_CURRENT_BINARY_DIR}/amsph_kernel_source.c)
  set(table_c ${CMAKE_CURRENT_BINARY_DIR}/amsph_kernel_table.c)
  file(GLOB headers ${kernel_dir}/*.h)
  list(TRANSFORM ARGN PREPEND ${kernel_dir}/ OUTPUT_VARIABLE kernel_paths)
  add_executable(amsph_embed_kernels ${PROJECT_SOURCE_DIR}/cmake/embed_kernels.c)
  add_custom_command(
    OUTPUT ${source_c} ${table_c}
    COMMAND amsph_embed_kernels ${source_c} ${table_c} ${kernel_dir} ${ARGN}
    DEPENDS amsph_embed_kernels ${kernel_paths} ${headers}
    COMMENT "Embedding kernels/ for OpenCL and generating the OpenMP kernel tables")
  target_sources(${target} PRIVATE ${source_c})
  foreach(dim 2 3)
    foreach(kernel 0 1)
      set(lib amsph_kernels_${dim}_${kernel})
      add_library(${lib} OBJECT ${table_c})
      target_include_directories(${lib} PRIVATE ${kernel_dir} ${PROJECT_SOURCE_DIR}/host)
      target_compile_definitions(${lib} PRIVATE AMSPH_DIM=${dim} AMSPH_KERNEL=${kernel}
        AMSPH_DOUBLE=$<BOOL:${AMSPH_DOUBLE}> AMSPH_OMP_TABLE=amsph_omp_kernels_${dim}_${kernel})
      amsph_set_warnings(${lib})
      # OpenCL C's math sets no errno and traps nothing: the C build of the
      # kernels may inline sqrt and keep loops free of libm calls alike.
      if(CMAKE_C_COMPILER_ID MATCHES "GNU|Clang")
        target_compile_options(${lib} PRIVATE -fno-math-errno -fno-trapping-math)
      endif()
      if(AMSPH_OPENMP)
        target_link_libraries(${lib} PRIVATE OpenMP::OpenMP_C)
      endif()
      set_target_properties(${lib} PROPERTIES POSITION_INDEPENDENT_CODE ON)
      target_sources(${target} PRIVATE $<TARGET_OBJECTS:${lib}>)
    endforeach()
  endforeach()
endfunction()
