#!/usr/bin/env bash
# Runs the bundle of tools/gpu_build.sh on the accelerator machine, from the
# repository root there (the tests read cases/ and tests/ of this tree).
#
#   tools/gpu_run.sh BUNDLE[.tar.gz] STAGE [BUILD] [-R REGEX]
#     STAGE  devices  the GPU, the driver libraries found, `amsph devices` of each build
#            tests    the build's ctest suite (tools/gpu_tests.py), -R to pick tests
#            bench    grid sort and the 3D dam breaks' throughput on each backend
#     BUILD  host (OpenCL on the GPU, OpenMP on host threads) or offload (OpenCL
#            and OpenMP both on the GPU); default: both
#
# It finds the NVIDIA driver's libcuda.so.1 (for libgomp's nvptx plugin) and
# libnvidia-opencl.so.1; where no OpenCL vendor file names the latter, it
# writes one and points the bundle's ICD loader at it (OCL_ICD_VENDORS).
# A stage fails (status 1) when a test fails or when a GPU path is missing:
# OpenCL without an NVIDIA device, or the offload build without an offload
# device. AMSPH_GPU_REQUIRED=0 rehearses it on a machine without a GPU.
# Work files and logs go to AMSPH_GPU_WORK (default /tmp/amsph-gpu).
set -euo pipefail
cd "$(dirname "$0")/.."
source_dir=$PWD
usage() {
    sed -n '2,18p' "$0" | sed 's/^# \{0,1\}//' >&2
    exit 2
}
[ $# -ge 2 ] || usage
bundle=$1 stage=$2
shift 2
[[ $stage =~ ^(devices|tests|bench)$ ]] || usage
builds="host offload"
if [ $# -gt 0 ] && [[ $1 != -* ]]; then builds=$1; shift; fi
work=${AMSPH_GPU_WORK:-/tmp/amsph-gpu}
required=${AMSPH_GPU_REQUIRED:-1}
mkdir -p "$work"
failed=0

fail() {
    echo "gpu_run: $*" >&2
    failed=1
}

if [[ $bundle == *.tar.gz ]]; then
    tar -C "$work" -xzf "$bundle"
    bundle=$work/$(basename "$bundle" .tar.gz)
fi
[ -f "$bundle/MANIFEST" ] || { echo "gpu_run: $bundle is not a bundle of tools/gpu_build.sh" >&2; exit 2; }
for b in $builds; do
    [ -x "$bundle/$b/amsph" ] || { echo "gpu_run: no build '$b' in $bundle (host, offload)" >&2; exit 2; }
done

# The bundle runs on the machine's glibc: it must be as new as the build's.
needed=$(sed -n 's/^glibc needed: //p' "$bundle/MANIFEST")
have=$(getconf GNU_LIBC_VERSION | cut -d' ' -f2)
if [ "$(printf '%s\n%s\n' "$needed" "$have" | sort -V | head -1)" != "$needed" ]; then
    echo "gpu_run: this machine's glibc is $have, the bundle needs $needed" >&2
    exit 1
fi
built_from=$(sed -n 's/^source: \([0-9a-f]*\).*/\1/p' "$bundle/MANIFEST")
[ "$built_from" = "$(git rev-parse HEAD 2>/dev/null || true)" ] ||
    echo "gpu_run: note: the bundle was built from $built_from, this tree is $(git rev-parse --short HEAD 2>/dev/null || echo 'not a git checkout')"

# Path of driver library $1: from the loader's cache, else the usual folders.
driver_library() {
    local path dir
    path=$(ldconfig -p 2>/dev/null | awk -v n="$1" '$1 == n && /x86-64/ {print $NF; exit}')
    local search=${LD_LIBRARY_PATH:-}
    for dir in ${search//:/ } /usr/local/nvidia/lib64 /usr/local/nvidia/lib \
        /usr/lib/x86_64-linux-gnu /lib/x86_64-linux-gnu /usr/lib64; do
        [ -n "$path" ] || [ ! -e "$dir/$1" ] || path=$dir/$1
    done
    [ -n "$path" ] || path=$(find /usr /opt -name "$1" -not -path '*/stubs/*' 2>/dev/null | head -1)
    echo "$path"
}

cuda=$(driver_library libcuda.so.1)
opencl=$(driver_library libnvidia-opencl.so.1)
for lib in "$cuda" "$opencl"; do # their own dependencies sit beside them
    [ -z "$lib" ] || export LD_LIBRARY_PATH=$(dirname "$lib")${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
done
if [ -z "${OCL_ICD_VENDORS:-}" ] && [ -n "$opencl" ] &&
    ! grep -qs nvidia /etc/OpenCL/vendors/*.icd; then
    mkdir -p "$work/icd"
    echo "$opencl" >"$work/icd/nvidia.icd"
    export OCL_ICD_VENDORS=$work/icd
fi

# Whether build $1 reaches the GPU on both backends (prints `amsph devices`).
check_devices() {
    local listing
    listing=$("$bundle/$1/amsph" devices 2>&1) || true
    echo "$listing" | sed "s/^/$1: /"
    if ! echo "$listing" | grep -q '^opencl --device .*NVIDIA'; then
        [ "$required" = 0 ] || fail "$1: OpenCL lists no NVIDIA device"
    fi
    if [ "$1" = offload ] && ! echo "$listing" | grep -q 'target offload, device'; then
        [ "$required" = 0 ] || fail "offload: no OpenMP offload device (libcuda.so.1: ${cuda:-not found})"
    fi
}

run_tests() { # build, options of gpu_tests.py run...
    local build=$1 env=(AMSPH_REQUIRE_OPENCL="$required")
    shift
    echo "== tests, $build build"
    [ "$build" != offload ] || [ "$required" = 0 ] || env+=(OMP_TARGET_OFFLOAD=MANDATORY)
    env "${env[@]}" python3 tools/gpu_tests.py run "$bundle/$build/tests.json" "$bundle/$build" \
        "$source_dir" "$work/$build" --timeout 540 "$@" || fail "$build: tests failed"
}

# Benchmarks as in BENCHMARKS.md ("On an NVIDIA H200"): the grid sort of 1e6
# and 1e7 random particles, and `bench throughput --kernels` (ms per step, per
# module and per kernel) of the fluid and the AM dam breaks at 1e5 and 1e6
# particles on each backend, at 1e7 on OpenCL; each command limited to
# AMSPH_GPU_BENCH_TIMEOUT seconds (default 120), so that one slow size does
# not take the call's time.
run_bench() {
    local amsph=$bundle/$1/amsph limit=${AMSPH_GPU_BENCH_TIMEOUT:-120} backend scene n sizes
    echo "== bench, $1 build"
    for backend in openmp opencl; do
        for n in 1000000 10000000; do
            timeout -k 5 "$limit" "$amsph" bench grid --particles $n --repeat 10 --backend $backend ||
                fail "$1: bench grid $n on $backend"
        done
        sizes="100000 1000000"
        [ $backend = openmp ] || sizes="$sizes 10000000"
        for scene in cases/validation/dambreak_3d.yaml cases/bench/am_dambreak_3d.yaml; do
            for n in $sizes; do
                timeout -k 5 "$limit" "$amsph" bench throughput $scene --particles $n --steps 10 --kernels \
                    --warmup 3 --backend $backend || fail "$1: bench throughput $scene $n on $backend"
            done
        done
    done
}

echo "bundle: $(head -2 "$bundle/MANIFEST" | tr '\n' ' ')"
echo "glibc $have; libcuda.so.1: ${cuda:-not found}; libnvidia-opencl.so.1: ${opencl:-not found};" \
    "OpenCL vendors: ${OCL_ICD_VENDORS:-/etc/OpenCL/vendors}"
if command -v nvidia-smi >/dev/null; then nvidia-smi -L || true; fi
for b in $builds; do
    check_devices "$b"
    case $stage in
    tests) run_tests "$b" "$@" ;;
    bench) run_bench "$b" ;;
    esac
done
exit $failed
