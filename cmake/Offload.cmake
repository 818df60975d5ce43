# AMSPH_OPENMP_OFFLOAD=nvptx: every work-item loop of the openmp backend's
# kernels becomes an OpenMP target region (kernels/device.h) that GCC also
# compiles for NVIDIA GPUs (Debian: gcc-12-offload-nvptx). Each executable's
# link builds its device image (mkoffload), with the device's libm. Without a
# GPU at run time the target regions run on host threads.
if(NOT AMSPH_OPENMP_OFFLOAD STREQUAL "nvptx")
  message(FATAL_ERROR "AMSPH_OPENMP_OFFLOAD must be empty or nvptx, got '${AMSPH_OPENMP_OFFLOAD}'")
endif()
if(NOT AMSPH_OPENMP OR NOT CMAKE_C_COMPILER_ID STREQUAL "GNU")
  message(FATAL_ERROR "AMSPH_OPENMP_OFFLOAD=nvptx needs AMSPH_OPENMP=ON and GCC "
    "(the C compiler is ${CMAKE_C_COMPILER_ID})")
endif()

set(offload_options -foffload=nvptx-none -foffload-options=nvptx-none=-misa=${AMSPH_OFFLOAD_ARCH}
  -foffload-options=nvptx-none=-lm)
include(CheckCSourceCompiles)
set(CMAKE_REQUIRED_FLAGS ${OpenMP_C_FLAGS})
set(CMAKE_REQUIRED_LINK_OPTIONS ${offload_options})
check_c_source_compiles("
int main(void)
{
    int x = 0;
#pragma omp target map(tofrom: x)
    x = 1;
    return x - 1;
}" AMSPH_NVPTX_OFFLOAD_WORKS)
unset(CMAKE_REQUIRED_FLAGS)
unset(CMAKE_REQUIRED_LINK_OPTIONS)
if(NOT AMSPH_NVPTX_OFFLOAD_WORKS)
  message(FATAL_ERROR "AMSPH_OPENMP_OFFLOAD=nvptx: ${CMAKE_C_COMPILER} cannot build nvptx offload "
    "code for ${AMSPH_OFFLOAD_ARCH}: install GCC's nvptx offload compiler (Debian: "
    "gcc-12-offload-nvptx); a CUDA ptxas on PATH checks the PTX and must know AMSPH_OFFLOAD_ARCH "
    "(see CMakeFiles/CMakeError.log)")
endif()

add_compile_definitions(AMSPH_OMP_OFFLOAD=1)
add_compile_options(${offload_options})
# The link needs -fopenmp to build the device image; GCC 12's offload table
# object is not position independent, so a PIE would get text relocations.
add_link_options(${OpenMP_C_FLAGS} ${offload_options} -no-pie)
