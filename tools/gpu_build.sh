#!/usr/bin/env bash
# Builds amsph for the accelerator machine (an NVIDIA GPU with its driver, no
# network, no package manager) and packs it into one self-contained file.
# Two Release builds, float, each with its test executables:
#   host     OpenCL backend + OpenMP backend on host threads (the default build)
#   offload  OpenCL backend + OpenMP backend offloaded to the GPU
#            (AMSPH_OPENMP_OFFLOAD=nvptx, GCC's nvptx offload compiler)
# The executables find the shared libraries they load (HDF5, libyaml, the
# ocl-icd OpenCL loader, libgomp and its nvptx plugin, ...) in the bundle's
# lib/ through their RPATH $ORIGIN/../lib; glibc and the NVIDIA driver come
# from the machine. tools/gpu_run.sh runs it there.
#
#   tools/gpu_build.sh [BUNDLE]       (default: gpu-bundle, ignored by git)
#
# Writes BUNDLE/ and BUNDLE.tar.gz (carry the latter). Needs, on Debian 12:
# build-essential cmake pkg-config ocl-icd-opencl-dev opencl-c-headers
# libhdf5-dev libyaml-dev gcc-12-offload-nvptx python3. Where CUDA's ptxas and
# nvlink are on PATH it also assembles and links the GPU code for sm_90 (H100)
# as the driver will. AMSPH_JOBS sets the build's parallelism (default 2).
set -euo pipefail
cd "$(dirname "$0")/.."
source_dir=$PWD
bundle=$(realpath -m "${1:-gpu-bundle}")
jobs=${AMSPH_JOBS:-2}
arch=sm_80 # PTX of GCC 12's newest target; the driver compiles it for the H100 (sm_90)

# glibc's own libraries: the machine's must be used, with its loader.
glibc='^(ld-linux-x86-64\.so\.2|libc\.so\.6|libm\.so\.6|libmvec\.so\.1|libpthread\.so\.0|libdl\.so\.2|librt\.so\.1|libresolv\.so\.2|libutil\.so\.1|libanl\.so\.1)$'

build() { # name, offload (empty or nvptx)
    local dir=build-gpu-$1 log
    log=$(mktemp)
    {
        cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=Release -DAMSPH_OPENCL=ON -DAMSPH_OPENMP=ON \
            -DAMSPH_DOUBLE=OFF -DAMSPH_WERROR=ON -DAMSPH_OPENMP_OFFLOAD="$2" -DAMSPH_OFFLOAD_ARCH=$arch \
            -DCMAKE_SKIP_BUILD_RPATH=ON \
            "-DCMAKE_EXE_LINKER_FLAGS=-Wl,--disable-new-dtags -Wl,-rpath,\$ORIGIN/../lib" &&
            cmake --build "$dir" -j"$jobs"
    } >"$log" 2>&1 || { tail -40 "$log" >&2; echo "gpu_build: building $dir failed" >&2; exit 1; }
    rm -f "$log"
}

# Copies build $1's executables and their test list into the bundle.
pack() {
    mkdir -p "$bundle/$1"
    python3 tools/gpu_tests.py list "build-gpu-$1" "$source_dir" "$bundle/$1/tests.json" |
        while read -r exe; do cp "$exe" "$bundle/$1/"; done
}

# Copies every library the bundled ELF files load, except glibc's, into lib/
# (DT_RPATH, unlike DT_RUNPATH, also serves the libraries' own dependencies
# and libgomp's dlopen of its plugin).
pack_libraries() {
    mkdir -p "$bundle/lib"
    cp -L "$(gcc -print-file-name=libgomp-plugin-nvptx.so.1)" "$bundle/lib/"
    find "$bundle" -type f \( -perm -u+x -o -name '*.so*' \) -exec ldd {} + 2>/dev/null |
        awk '$2 == "=>" && $3 ~ /^\// {print $1, $3}' | sort -u |
        while read -r name path; do
            [[ $name =~ $glibc ]] || [ -e "$bundle/lib/$name" ] || cp -L "$path" "$bundle/lib/$name"
        done
}

# Every library the bundle's programs load, glibc's aside, comes from the
# bundle, with LD_LIBRARY_PATH cleared; and both builds start from there.
check_self_contained() {
    local outside
    outside=$(find "$bundle" -type f -perm -u+x ! -name '*.so*' -exec env -u LD_LIBRARY_PATH ldd {} + |
        awk -v glibc="$glibc" -v inside="$bundle/" \
            '$2 == "=>" && $1 !~ glibc && index($3, inside) != 1 {print $1, $3}' | sort -u)
    [ -z "$outside" ] || { echo "gpu_build: loaded from outside the bundle: $outside" >&2; exit 1; }
    for b in host offload; do env -u LD_LIBRARY_PATH "$bundle/$b/amsph" devices >/dev/null; done
    echo "self-contained: every library but glibc's loads from $bundle/lib"
}

# The offload image's PTX, assembled and linked for sm_90 by CUDA's tools,
# as the driver's JIT does on the GPU.
check_ptx() {
    if ! command -v ptxas >/dev/null || ! command -v nvlink >/dev/null; then
        echo "PTX check: skipped (no CUDA ptxas and nvlink on PATH)"
        return
    fi
    local ptx
    ptx=$(mktemp -d)
    python3 - "$bundle/offload/amsph" "$ptx" <<'EOF'
import sys
data = open(sys.argv[1], "rb").read()
start, n = data.find(b"// BEGIN PREAMBLE"), 0
while start >= 0:
    end = data.index(b"\0", start)
    open(f"{sys.argv[2]}/module{n:03d}.ptx", "wb").write(data[start:end])
    start, n = data.find(b"// BEGIN PREAMBLE", end), n + 1
EOF
    local modules=("$ptx"/module*.ptx)
    for m in "${modules[@]}"; do ptxas -arch=sm_90 -c "$m" -o "${m%.ptx}.o"; done
    nvlink -arch=sm_90 "$ptx"/module*.o -o "$ptx/image.cubin" 2>&1 | grep -v 'Stack size for entry' || true
    echo "PTX check: ${#modules[@]} modules of offload/amsph assembled and linked for sm_90" \
        "($(ptxas --version | tail -1))"
    rm -rf "$ptx"
}

manifest() {
    {
        echo "amsph GPU bundle, built $(date -u +%Y-%m-%dT%H:%MZ) on $(uname -n)"
        echo "source: $(git rev-parse HEAD)$(git diff --quiet HEAD -- . || echo ' (with uncommitted changes)')"
        echo "compiler: $(gcc --version | head -1)"
        echo "host: AMSPH_OPENCL=ON AMSPH_OPENMP=ON, Release, float"
        echo "offload: as host, with AMSPH_OPENMP_OFFLOAD=nvptx AMSPH_OFFLOAD_ARCH=$arch"
        echo "glibc needed: $(find "$bundle" -type f \( -perm -u+x -o -name '*.so*' \) \
            -exec objdump -T {} + 2>/dev/null | grep -o 'GLIBC_2\.[0-9]*' | sort -t. -k2 -n -u |
            tail -1 | cut -d_ -f2)"
    } >"$bundle/MANIFEST"
}

rm -rf "$bundle" "$bundle.tar.gz"
build host ""
build offload nvptx
pack host
pack offload
pack_libraries
check_self_contained
manifest
check_ptx
tar -C "$(dirname "$bundle")" -czf "$bundle.tar.gz" "$(basename "$bundle")"

cat "$bundle/MANIFEST"
echo "libraries: $(ls "$bundle/lib" | tr '\n' ' ')"
du -sh "$bundle" "$bundle.tar.gz"
echo "next: carry $(basename "$bundle").tar.gz to the GPU machine and run tools/gpu_run.sh there"
