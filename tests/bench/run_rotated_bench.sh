#!/usr/bin/env bash
# Robustness benchmark: the recovery benchmark (run_recover_bench.sh, libcbr
# against `tetgen -pYQ`) on copies of the shared surfaces turned by random
# rotations, scalings and shifts (rotate_surface.py; one copy per surface
# and seed). A surface's position in space must not decide whether it is
# recovered; rotated CAD shapes, whose planar faces are then only nearly
# planar, are what this finds.
#
#   tests/bench/run_rotated_bench.sh [--seeds N] [run_recover_bench.sh options] [SURFACE...]
#
#   --seeds N     rotations per surface, seeds 1..N (default 2)
#   SURFACE...    names in the shared data (default: every surface)
#
# Other options (--csv, --verify, --timeout, --repeat, --keep) go to
# run_recover_bench.sh, which builds libcbr and prints the table; the
# rotated copies are named SURFACE-rSEED.
set -eu

here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)
seeds=2
pass=()
names=()
while [ $# -gt 0 ]; do
    case $1 in
        --seeds) [ $# -ge 2 ] || { echo "--seeds needs a number" >&2; exit 1; }; seeds=$2; shift 2 ;;
        --seeds=*) seeds=${1#--seeds=}; shift ;;
        --csv|--timeout|--repeat) [ $# -ge 2 ] || { echo "$1 needs a value" >&2; exit 1; }; pass+=("$1" "$2"); shift 2 ;;
        -*) pass+=("$1"); shift ;;
        *) names+=("${1%.off}"); shift ;;
    esac
done
case $seeds in ''|*[!0-9]*) echo "--seeds: a positive integer, not '$seeds'" >&2; exit 1 ;; esac
data=${CBR_SHARED_DATA_DIR:-$repo/../shared/data}/surfaces
[ -d "$data" ] || { echo "no shared surfaces in $data (set CBR_SHARED_DATA_DIR)" >&2; exit 1; }
if [ ${#names[@]} -eq 0 ]; then
    for f in "$data"/*.off; do names+=("$(basename "$f" .off)"); done
fi
work=$(mktemp -d "${TMPDIR:-/tmp}/cbr-rotated.XXXXXX")
trap 'rm -rf "$work"' EXIT
for name in "${names[@]}"; do
    [ -f "$data/$name.off" ] || { echo "no surface $name in $data" >&2; exit 1; }
    for seed in $(seq 1 "$seeds"); do
        python3 "$here/rotate_surface.py" "$data/$name.off" "$work/$name-r$seed.off" "$seed"
    done
done
echo "== $((${#names[@]} * seeds)) rotated copies in $work"
"$here/run_recover_bench.sh" ${pass[@]+"${pass[@]}"} "$work"
