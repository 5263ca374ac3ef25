#!/usr/bin/env bash
# Boundary recovery benchmark: libcbr (`cbr recover`) against TetGen 1.5
# (`tetgen -pYQ`, the Debian package) on every surface of the shared data,
# one after the other in the same run, and prints per mesh and in total:
# success, faces missing after Delaunay, faces recovered by flips, Steiner
# points (libcbr: inside the domain, and all), wall time and the time ratio
# libcbr / TetGen.
#
#   tests/bench/run_recover_bench.sh [options] [DATA_DIR] [SURFACE...]
#
#   DATA_DIR      directory of .off surfaces (default $CBR_SHARED_DATA_DIR/surfaces,
#                 else <repo>/../shared/data/surfaces; OFF only: TetGen's
#                 Steiner points are its output nodes minus the OFF's points)
#   SURFACE...    only these surfaces: paths, or names in DATA_DIR with or
#                 without .off (default: every *.off in DATA_DIR)
#   --csv FILE    also write the table (per mesh, then the totals) as CSV
#   --verify      check both outputs with the independent checker
#                 ../shared/tools/verify (`cbr-verify`; needs libcgal-dev;
#                 building it takes minutes; found next to
#                 $CBR_SHARED_DATA_DIR when that is set). $CBR_VERIFY names
#                 a prebuilt cbr-verify instead.
#   --timeout S   seconds allowed to each run (default $CBR_BENCH_TIMEOUT or 300)
#   --repeat N    run each tool N times on each surface, one run after the
#                 other, and report the median wall time (default
#                 $CBR_BENCH_REPEAT or 1; every run makes the same mesh)
#   --threads N   pass --threads N to cbr (1: libcbr on one thread, as the
#                 peers run; default: cbr's own, as many as the hardware
#                 runs at once; the meshes are the same either way)
#   --keep        keep the outputs (the work directory is printed)
#
# Build directory of libcbr and `cbr` (Release): $CBR_BENCH_BUILD (default
# <repo>/build-bench/recover); of cbr-verify: $CBR_BENCH_VERIFY_BUILD (default
# <repo>/build-bench/verify). Extra CMake arguments: $CBR_BENCH_CMAKE_ARGS.
# Installs the Debian package tetgen when it is missing (and says so).
#
# Exit status: 0 when the benchmark ran (whatever each mesh did), 1 on a
# bad command line or a failed build. `cbr recover` exits 0 on success, 3
# when it could not recover every face; any other code is reported as ERROR.
set -eu

here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)
# shellcheck source=bench_common.sh
. "$here/bench_common.sh"
build=${CBR_BENCH_BUILD:-$repo/build-bench/recover}
verify_build=${CBR_BENCH_VERIFY_BUILD:-$repo/build-bench/verify}
jobs=$(nproc 2>/dev/null || echo 2)
extra=${CBR_BENCH_CMAKE_ARGS:-}
limit=${CBR_BENCH_TIMEOUT:-300}
repeat=${CBR_BENCH_REPEAT:-1}
thread_args=()
data=
csv=
verify=0
keep=0
surfaces=()

usage() {
    sed -n '2,/^set -eu/p' "$0" | sed -e '/^set -eu/d' -e 's/^# \{0,1\}//' >&2
    exit 1
}

while [ $# -gt 0 ]; do
    case $1 in
        --csv) [ $# -ge 2 ] || usage; csv=$2; shift 2 ;;
        --csv=*) csv=${1#--csv=}; shift ;;
        --verify) verify=1; shift ;;
        --threads) [ $# -ge 2 ] || usage; thread_args=(--threads "$2"); shift 2 ;;
        --threads=*) thread_args=(--threads "${1#--threads=}"); shift ;;
        --timeout) [ $# -ge 2 ] || usage; limit=$2; shift 2 ;;
        --timeout=*) limit=${1#--timeout=}; shift ;;
        --repeat) [ $# -ge 2 ] || usage; repeat=$2; shift 2 ;;
        --repeat=*) repeat=${1#--repeat=}; shift ;;
        --keep) keep=1; shift ;;
        -h|--help) usage ;;
        --) shift; break ;;
        -*) echo "run_recover_bench.sh: unknown option '$1'" >&2; usage ;;
        *)
            if [ -z "$data" ] && [ ${#surfaces[@]} -eq 0 ] && [ -d "$1" ]; then
                data=$1
            else
                surfaces+=("$1")
            fi
            shift ;;
    esac
done
surfaces+=("$@")
case $limit in ''|*[!0-9]*|0) echo "run_recover_bench.sh: --timeout needs whole seconds (at least 1)" >&2; exit 1 ;; esac
check_repeat run_recover_bench.sh

bench_surfaces run_recover_bench.sh "$data" "${surfaces[@]}"
bench_build_cbr run_recover_bench.sh

as_root() {
    if [ "$(id -u)" -eq 0 ]; then "$@"; elif command -v sudo >/dev/null 2>&1; then sudo "$@"; else return 1; fi
}

have_tetgen=1
if ! command -v tetgen >/dev/null 2>&1; then
    echo "== tetgen is missing: installing the Debian package tetgen (apt-get install -y tetgen)"
    if ! as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y tetgen >/dev/null; then
        as_root apt-get update >/dev/null 2>&1 || true
        as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y tetgen >/dev/null || true
    fi
    if command -v tetgen >/dev/null 2>&1; then
        echo "   installed: $(command -v tetgen)"
    else
        echo "   could not install tetgen: its columns stay empty" >&2
        have_tetgen=0
    fi
fi

checker=
if [ "$verify" -eq 1 ]; then
    if [ -n "${CBR_VERIFY:-}" ]; then
        checker=$CBR_VERIFY
        echo "== cbr-verify: $checker (from CBR_VERIFY)"
    else
        # ../shared/tools next to ../shared/data ($CBR_SHARED_DATA_DIR, else next to the repository).
        tool=${CBR_SHARED_DATA_DIR:-$repo/../shared/data}/../tools/verify/build.sh
        echo "== cbr-verify: build in $verify_build (minutes the first time)"
        if [ ! -f "$tool" ]; then
            # A worktree or clone away from ../shared, CBR_SHARED_DATA_DIR unset.
            echo "   no $tool: set CBR_VERIFY to a built cbr-verify; no verification" >&2
            checker=
        elif checker=$(bash "$tool" "$verify_build" 2>"$build/verify-build.log" | tail -n 1) && [ -x "$checker" ]; then
            :
        else
            echo "   cbr-verify could not be built (see $build/verify-build.log; it needs" >&2
            echo "   apt-get install -y libcgal-dev libgmp-dev libmpfr-dev): no verification" >&2
            checker=
        fi
    fi
    if [ -n "$checker" ] && [ ! -x "$checker" ]; then
        echo "   $checker is not executable: no verification" >&2
        checker=
    fi
fi

bench_workdir recover

# The number after a Table I label that cbr prints (src/cli/table_one.cpp:
# "  recovered by flips   4"); stdout first, stderr as well.
table_value() { cat "$out" "$err" | sed -n "s/^  $1  *\([0-9.eE+-]*\)\$/\1/p" | head -n 1; }

# A whole-number value of the `cbr recover --json` report ("steiner_inside": 4).
json_value() { sed -n "s/.*\"$1\": *\([0-9][0-9]*\).*/\1/p" "$2" 2>/dev/null | head -n 1; }

# Counts of an OFF file's header: "nv nf".
off_counts() {
    awk '{ sub(/#.*/, "") } NF == 0 { next }
         !seen { seen = 1; sub(/^[A-Za-z]*OFF/, ""); if (NF == 0) next }
         { print $1, $2; exit }' "$1"
}

# The first line of a file, made safe for one CSV field.
first_line() { head -n 1 "$1" 2>/dev/null | tr -d '\r' | tr ',"' ';'"'" | cut -c1-160; }

verify_one() { # INPUT OUTPUT NAME -> sets vstat, vjson
    vjson=$work/$3.verify.json
    local out=$vjson err=$work/$3.verify.err
    timed "$checker" "$1" "$2" --json
    case $rc in
        0) vstat=ok ;;
        1) vstat=FAIL ;;
        timeout) vstat=TIMEOUT ;;
        *) vstat=ERROR ;;
    esac
}

raw=$work/raw.csv
echo "file,faces,points,cbr_status,cbr_exit,cbr_missing,cbr_flips,cbr_steiner,cbr_steiner_all,cbr_seconds,cbr_delaunay_s,cbr_recovery_s,cbr_total_s,tetgen_status,tetgen_exit,tetgen_steiner,tetgen_seconds,cbr_verify,cbr_verify_json,tetgen_verify,tetgen_verify_json,note" >"$raw"

n=${#files[@]}
i=0
[ "$repeat" -gt 1 ] && runs=", median of $repeat runs" || runs=
echo "== run: ${n} surfaces, ${limit} s limit per run${runs}${checker:+, verified by $checker}"
for f in "${files[@]}"; do
    i=$((i + 1))
    name=$(basename "$f" .off)
    dir=$work/$name
    mkdir -p "$dir"
    read -r npoints nfaces <<EOF
$(off_counts "$f")
EOF
    note=

    # libcbr
    out=$dir/cbr.out err=$dir/cbr.err
    timed_runs "$repeat" "$cbr" recover "$f" -o "$dir/cbr.mesh" --json "$dir/cbr.json" "${thread_args[@]}"
    cbr_exit=$rc
    case $rc in
        0) cbr_status=ok ;;
        3) cbr_status=FAILED ;;
        timeout) cbr_status=TIMEOUT ;;
        *) cbr_status=ERROR ;;
    esac
    cbr_secs=$secs
    cbr_missing=$(table_value "faces missing after Delaunay")
    cbr_flips=$(table_value "recovered by flips")
    # Steiner: those of the domain mesh (bounded regions), as TetGen counts;
    # Steiner (all): the exterior's too (dropped with it).
    cbr_steiner=$(json_value steiner_inside "$dir/cbr.json")
    cbr_steiner_all=$(table_value "Steiner points remaining")
    times=$(cat "$out" "$err" | sed -n 's/^  time: Delaunay \([0-9.]*\) s, recovery \([0-9.]*\) s, total \([0-9.]*\) s.*/\1 \2 \3/p' | head -n 1)
    read -r cbr_del cbr_rec cbr_tot <<EOF
$times
EOF
    if [ "$cbr_status" = ok ] && [ ! -s "$dir/cbr.mesh" ]; then
        cbr_status=ERROR
        note="cbr: exit 0 but no output"
    elif [ "$cbr_status" = ERROR ]; then
        note="cbr exit $rc: $(first_line "$err")"
    fi

    # TetGen, on a copy so that nothing is written next to the shared data.
    tg_status='' tg_exit='' tg_steiner='' tg_secs=''
    if [ "$have_tetgen" -eq 1 ]; then
        mkdir -p "$dir/tetgen"
        cp "$f" "$dir/tetgen/$name.off"
        out=$dir/tetgen.out err=$dir/tetgen.err
        timed_runs "$repeat" tetgen -pYQ "$dir/tetgen/$name.off"
        tg_exit=$rc
        tg_secs=$secs
        node=$dir/tetgen/$name.1.node
        if [ "$rc" = timeout ]; then
            tg_status=TIMEOUT
        elif [ "$rc" -eq 0 ] && [ -s "$node" ] && [ -s "$dir/tetgen/$name.1.ele" ]; then
            tg_status=ok
            nodes=$(awk '{ sub(/#.*/, "") } NF { print $1; exit }' "$node")
            tg_steiner=$((nodes - npoints))
        else
            tg_status=FAILED
            msg=$(grep -m 1 -i 'error\|abort\|fail\|self-inters\|intersect' "$out" "$err" 2>/dev/null | sed 's/^[^:]*://' || true)
            if [ "$rc" -eq 0 ]; then msg="no .1.node/.1.ele written${msg:+; $msg}"; fi
            note="${note:+$note; }tetgen exit $rc${msg:+: $(printf '%s' "$msg" | tr ',"' ';'"'" | cut -c1-120)}"
        fi
    fi

    # Independent checks.
    cv='' cvj='' tv='' tvj=''
    if [ -n "$checker" ]; then
        if [ "$cbr_status" = ok ]; then
            verify_one "$f" "$dir/cbr.mesh" "$name.cbr"
            cv=$vstat cvj=$vjson
        fi
        if [ "$tg_status" = ok ]; then
            verify_one "$f" "$dir/tetgen/$name.1.ele" "$name.tetgen"
            tv=$vstat tvj=$vjson
        fi
    fi

    echo "$name,$nfaces,$npoints,$cbr_status,$cbr_exit,$cbr_missing,$cbr_flips,$cbr_steiner,$cbr_steiner_all,$cbr_secs,$cbr_del,$cbr_rec,$cbr_tot,$tg_status,$tg_exit,$tg_steiner,$tg_secs,$cv,$cvj,$tv,$tvj,\"$note\"" >>"$raw"
    printf '   [%d/%d] %-36s cbr %-7s %8s s   tetgen %-7s %8s s%s\n' "$i" "$n" "$name" "$cbr_status" "$cbr_secs" \
        "${tg_status:-n/a}" "${tg_secs:--}" "${checker:+   verify cbr ${cv:--} tetgen ${tv:--}}"
    if [ "$keep" -eq 0 ]; then
        rm -rf "$dir"
    fi
done

echo
if command -v python3 >/dev/null 2>&1; then
    python3 "$here/recover_bench_table.py" "$raw" ${csv:+--csv "$csv"}
else
    echo "(python3 not found: the raw table)"
    cat "$raw"
    if [ -n "$csv" ]; then cp "$raw" "$csv"; fi
fi
