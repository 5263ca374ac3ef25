#!/bin/sh
# Independent verification: every surface of ../shared/data/surfaces goes
# through `cbr recover`, and the .mesh it writes is checked by cbr-verify
# (../shared/tools/verify), which shares no code with libcbr: every input
# triangle a tet face, no Steiner point on the surface, valid conforming
# tets covering exactly the enclosed volume.
#
#   test_verify.sh <cbr> <data dir> <verify build dir>
#
# The verifier comes from <data dir>/../tools/verify and is built once into
# <verify build dir> (reused while its sources are unchanged; the build needs
# libcgal-dev libgmp-dev libmpfr-dev and takes about 40 s). Exit 77 (skip)
# when the data, the verifier or the CGAL headers are absent.
#
# A surface that cbr recover cannot recover yet (exit 3: conforming recovery
# with Steiner points is not implemented) counts as "not recovered yet" and
# must leave no output file; any other exit code but 0 is a failure.
set -u

if [ $# -ne 3 ]; then
    echo "usage: $0 <cbr> <data dir> <verify build dir>" >&2
    exit 2
fi
cbr=$1
data=$2
build=$3

if [ ! -d "$data/surfaces" ]; then
    echo "SKIP: no shared data directory ($data)"
    exit 77
fi
verify_src=$(cd "$data/../tools/verify" 2> /dev/null && pwd)
if [ -z "$verify_src" ] || [ ! -f "$verify_src/build.sh" ]; then
    echo "SKIP: no independent verifier ($data/../tools/verify/build.sh)"
    exit 77
fi
if [ ! -f /usr/include/CGAL/version.h ] && [ ! -f /usr/local/include/CGAL/version.h ]; then
    echo "SKIP: CGAL headers are not installed (apt-get install libcgal-dev libgmp-dev libmpfr-dev)"
    exit 77
fi
[ -x "$cbr" ] || { echo "FAIL: $cbr is not an executable"; echo "0 passed, 1 failed"; exit 1; }

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
passed=0
failed=0

fail() {
    echo "FAIL: $*"
    failed=$((failed + 1))
}

# Build cbr-verify unless the binary is newer than all of its sources.
verifier=$build/cbr-verify
if [ -x "$verifier" ] && [ -z "$(find "$verify_src" -maxdepth 1 -type f -newer "$verifier" | head -n 1)" ]; then
    echo "cbr-verify: reusing $verifier"
else
    echo "cbr-verify: building into $build"
    if ! bash "$verify_src/build.sh" "$build" > "$tmp/build.out" 2> "$tmp/build.log" || [ ! -x "$verifier" ]; then
        fail "building cbr-verify: $(tail -n 20 "$tmp/build.log")"
        echo "$passed passed, $failed failed"
        exit 1
    fi
fi

total=0
verified=0
pending=0
for f in "$data"/surfaces/*; do
    [ -f "$f" ] || continue
    total=$((total + 1))
    name=$(basename "$f")
    name=${name%.*}
    out=$tmp/$name.mesh
    "$cbr" recover "$f" -o "$out" -q > "$tmp/out" 2> "$tmp/err"
    rc=$?
    case $rc in
    0)
        if [ ! -s "$out" ]; then
            fail "cbr recover $f exited with 0 but wrote no $name.mesh"
        elif "$verifier" "$f" "$out" > "$tmp/verify.out" 2> "$tmp/verify.err"; then
            verified=$((verified + 1))
            passed=$((passed + 1))
        else
            vrc=$?
            fail "cbr-verify rejects the mesh of $f (exit $vrc):"
            grep '^FAILED: ' "$tmp/verify.out" | cut -c 1-600 | sed 's/^/    /'
            sed 's/^/    /' "$tmp/verify.err"
        fi
        ;;
    3)
        if [ -e "$out" ]; then
            fail "cbr recover $f exited with 3 but left $name.mesh behind"
        else
            pending=$((pending + 1))
            passed=$((passed + 1))
            echo "not recovered yet: $name: $(head -n 1 "$tmp/err" | cut -c 1-160)"
        fi
        ;;
    *)
        fail "cbr recover $f exited with $rc: $(head -c 1000 "$tmp/err")"
        ;;
    esac
    rm -f "$out"
done

[ "$total" -gt 0 ] || fail "no surface in $data/surfaces"

echo "verified $verified of $total surfaces, $pending not recovered yet"
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
