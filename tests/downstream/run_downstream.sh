#!/bin/sh
# Downstream tests: use libcbr the way its users do, from an installed copy.
#
#   run_downstream.sh install <build-dir> <work-dir> <config>
#       cmake --install <build-dir> into <work-dir>/prefix (wiped first)
#   run_downstream.sh c|fortran|cmake <build-dir> <work-dir> <config>
#       c:       cc cube.c $(pkg-config --cflags --libs cbr), run it
#       fortran: gfortran -I$(pkg-config --variable=fmoddir cbr) cube.f90, run it
#       cmake:   configure, build and run cmake_consumer/ (find_package(cbr))
#
# The install step must have run first (ctest fixture cbr_downstream).
# Environment (set by tests/CMakeLists.txt):
#   CBR_LIBDIR     CMAKE_INSTALL_LIBDIR of the build (relative to the prefix)
#   CBR_VERSION    the project version
#   CBR_CC, CBR_CXX, CBR_FC   compilers (CBR_FC empty: no Fortran module)
#   CBR_EXTRA_FLAGS   extra compile/link flags (sanitizer builds)
# Exit 0: passed, 1: failed, 77: skipped because a tool is missing (said so).
set -eu

if [ $# -ne 4 ]; then
    echo "usage: $0 install|c|fortran|cmake <build-dir> <work-dir> <config>" >&2
    exit 2
fi
step=$1
build_dir=$2
work=$3
config=$4
here=$(cd "$(dirname "$0")" && pwd)
prefix=$work/prefix
libdir_rel=${CBR_LIBDIR:-lib}
extra=${CBR_EXTRA_FLAGS:-}

case $libdir_rel in
/*) echo "SKIP: CMAKE_INSTALL_LIBDIR is absolute ($libdir_rel): cannot install into a temporary prefix"
    exit 77 ;;
esac
libdir=$prefix/$libdir_rel

skip() { echo "SKIP: $*"; exit 77; }
fail() { echo "FAIL: $*"; exit 1; }
run() { echo "+ $*"; "$@"; }

need_install() {
    [ -f "$libdir/pkgconfig/cbr.pc" ] ||
        fail "$libdir/pkgconfig/cbr.pc missing: did the downstream_install test run and pass?"
}

# pkg-config as a user runs it, looking at the temporary prefix first.
use_pkg_config() {
    command -v pkg-config >/dev/null 2>&1 || skip "pkg-config not found"
    need_install
    PKG_CONFIG_PATH=$libdir/pkgconfig${PKG_CONFIG_PATH:+:$PKG_CONFIG_PATH}
    export PKG_CONFIG_PATH
    pc_prefix=$(pkg-config --variable=prefix cbr)
    [ "$pc_prefix" = "$prefix" ] ||
        fail "cbr.pc installed into $prefix says prefix=$pc_prefix: it must be written at install time (cmake --install --prefix)"
    pc_version=$(pkg-config --modversion cbr)
    [ "$pc_version" = "${CBR_VERSION:-$pc_version}" ] ||
        fail "pkg-config --modversion cbr is $pc_version, the project is $CBR_VERSION"
}

case $step in
install)
    rm -rf "$prefix"
    mkdir -p "$work"
    run cmake --install "$build_dir" --prefix "$prefix" --config "$config"
    need_install
    for f in "$prefix/include/cbr/cbr.h" "$libdir/libcbr.so" "$libdir/cmake/cbr/cbrConfig.cmake"; do
        [ -e "$f" ] || fail "$f was not installed"
    done
    echo "installed into $prefix"
    ;;

c)
    use_pkg_config
    cc=${CBR_CC:-cc}
    command -v "$cc" >/dev/null 2>&1 || skip "C compiler $cc not found"
    out=$work/c
    rm -rf "$out" && mkdir -p "$out"
    # shellcheck disable=SC2046,SC2086  # word splitting of the flags is meant
    run "$cc" -std=c99 -Wall -Wextra -pedantic -Werror $extra "$here/cube.c" \
        $(pkg-config --cflags --libs cbr) -lm -o "$out/cube"
    LD_LIBRARY_PATH=$libdir${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
    export LD_LIBRARY_PATH
    run "$out/cube"
    ;;

fortran)
    fc=${CBR_FC:-}
    [ -n "$fc" ] || skip "libcbr was configured without a Fortran compiler, so no Fortran module is installed"
    command -v "$fc" >/dev/null 2>&1 || skip "Fortran compiler $fc not found"
    use_pkg_config
    fmoddir=$(pkg-config --variable=fmoddir cbr)
    [ -f "$fmoddir/cbr.mod" ] || fail "no cbr.mod in fmoddir=$fmoddir"
    # The module's own procedures (cbr_f_string) are compiled code: they come
    # from the library cbr-fortran.pc names when it is installed.
    if pkg-config --exists cbr-fortran; then
        libs=$(pkg-config --libs cbr-fortran)
    else
        libs=$(pkg-config --libs cbr)
    fi
    out=$work/fortran
    rm -rf "$out" && mkdir -p "$out"
    # Compiled in its own directory so that only the installed cbr.mod is seen.
    # shellcheck disable=SC2086
    if ! (cd "$out" && run "$fc" -std=f2008 -Wall -Werror $extra -I"$fmoddir" \
              "$here/cube.f90" $libs -o "$out/cube"); then
        fail "could not build cube.f90 against the installed module (if cbr_f_string is unresolved, the module's object code is not installed: see cbr-fortran.pc)"
    fi
    LD_LIBRARY_PATH=$libdir${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
    export LD_LIBRARY_PATH
    run "$out/cube"
    ;;

cmake)
    need_install
    out=$work/cmake
    rm -rf "$out"
    set --
    [ -n "${CBR_CXX:-}" ] && set -- "$@" "-DCMAKE_CXX_COMPILER=$CBR_CXX"
    [ -n "$extra" ] && set -- "$@" "-DCMAKE_CXX_FLAGS=$extra" "-DCMAKE_EXE_LINKER_FLAGS=$extra"
    run cmake -S "$here/cmake_consumer" -B "$out" -DCMAKE_BUILD_TYPE=Release \
        "-DCMAKE_PREFIX_PATH=$prefix" "-DCBR_EXPECTED_VERSION=${CBR_VERSION:-}" "$@"
    run cmake --build "$out"
    # No LD_LIBRARY_PATH: the build-tree RPATH CMake sets must find libcbr.
    run "$out/cbr_consumer"
    ;;

*)
    echo "$0: unknown step '$step'" >&2
    exit 2
    ;;
esac
