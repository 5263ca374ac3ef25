#!/bin/sh
# Builds libcbr (Release), installs it into a temporary prefix, builds the
# benchmark against it and CGAL, and runs it:
#   tests/bench/run_delaunay_bench.sh [delaunay_bench arguments, e.g. 1e5 1e6]
# Build directories: $CBR_BENCH_BUILD (default <repo>/build-bench)/{lib,bench}.
# Extra CMake arguments for both builds: $CBR_BENCH_CMAKE_ARGS.
set -eu

here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)
build=${CBR_BENCH_BUILD:-$repo/build-bench}
jobs=$(nproc 2>/dev/null || echo 2)
extra=${CBR_BENCH_CMAKE_ARGS:-}

prefix=$(mktemp -d "${TMPDIR:-/tmp}/cbr-bench-prefix.XXXXXX")
trap 'rm -rf "$prefix"' EXIT INT TERM

echo "== libcbr: Release build in $build/lib"
# shellcheck disable=SC2086  # $extra is a list of arguments
cmake -S "$repo" -B "$build/lib" -DCMAKE_BUILD_TYPE=Release \
    -DCBR_BUILD_TESTS=OFF -DCBR_BUILD_CLI=OFF -DCMAKE_INSTALL_LIBDIR=lib $extra >/dev/null
cmake --build "$build/lib" -j "$jobs"
echo "== libcbr: install into $prefix"
cmake --install "$build/lib" --prefix "$prefix" >/dev/null

echo "== benchmark: build in $build/bench"
# shellcheck disable=SC2086
cmake -S "$here" -B "$build/bench" -DCMAKE_BUILD_TYPE=Release \
    "-DCMAKE_PREFIX_PATH=$prefix" -Dcbr_DIR="$prefix/lib/cmake/cbr" $extra >/dev/null
cmake --build "$build/bench" -j "$jobs"

echo "== run"
LD_LIBRARY_PATH=$prefix/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH} "$build/bench/delaunay_bench" "$@"
