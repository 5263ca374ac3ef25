# Shared by the benchmark scripts (sourced, bash): which surfaces to run
# and the Release build of `cbr`.

# bench_surfaces SCRIPT DATA [SURFACE...]: sets `data` (the directory of
# the shared surfaces: DATA if given, else $CBR_SHARED_DATA_DIR/surfaces,
# else ../shared/data/surfaces next to the repository `repo`) and `files`
# (absolute paths: the SURFACEs, as paths or names in `data`, or every
# .off in `data`). Exits with a message when there is none.
bench_surfaces() {
    local script=$1
    data=$2
    shift 2
    if [ -z "$data" ]; then
        data=${CBR_SHARED_DATA_DIR:-$repo/../shared/data}/surfaces
    fi
    if [ ! -d "$data" ]; then
        echo "$script: no data directory $data (give it as argument or set CBR_SHARED_DATA_DIR)" >&2
        exit 1
    fi
    data=$(cd "$data" && pwd)
    files=()
    if [ $# -eq 0 ]; then
        while IFS= read -r f; do files+=("$f"); done < <(find "$data" -maxdepth 1 -name '*.off' -type f | LC_ALL=C sort)
    else
        local s
        for s in "$@"; do
            if [ -f "$s" ]; then
                files+=("$(cd "$(dirname "$s")" && pwd)/$(basename "$s")")
            elif [ -f "$data/$s" ]; then
                files+=("$data/$s")
            elif [ -f "$data/$s.off" ]; then
                files+=("$data/$s.off")
            else
                echo "$script: no surface '$s' (neither a file nor in $data)" >&2
                exit 1
            fi
        done
    fi
    if [ ${#files[@]} -eq 0 ]; then
        echo "$script: no .off surface in $data" >&2
        exit 1
    fi
}

# bench_build_cbr SCRIPT: Release build of `cbr` from `repo` in `build`
# (extra CMake arguments in `extra`, `jobs` in parallel); sets `cbr`.
bench_build_cbr() {
    echo "== libcbr and cbr: Release build in $build"
    # A new build directory leaves the tests out; an existing one (a
    # developer's own build given as CBR_BENCH_BUILD) keeps its setting, so
    # that a benchmark run does not silently drop its test executables.
    local tests=-DCBR_BUILD_TESTS=OFF
    [ -f "$build/CMakeCache.txt" ] && tests=
    # shellcheck disable=SC2086  # $extra and $tests are lists of arguments
    cmake -S "$repo" -B "$build" -DCMAKE_BUILD_TYPE=Release $tests $extra >/dev/null
    cmake --build "$build" -j "$jobs" --target cbr_cli >/dev/null
    cbr=$build/cbr
    [ -x "$cbr" ] || { echo "$1: $cbr was not built" >&2; exit 1; }
}

# bench_workdir TAG: a temporary directory in `work`, removed at exit unless
# `keep` is 1.
bench_workdir() {
    work=$(mktemp -d "${TMPDIR:-/tmp}/cbr-$1-bench.XXXXXX")
    if [ "$keep" -eq 1 ]; then
        echo "== outputs kept in $work"
    else
        trap 'rm -rf "$work"' EXIT
        trap 'rm -rf "$work"; exit 130' INT TERM
    fi
}

now() { date +%s.%N; }
elapsed() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.3f", b - a }'; }

# timed CMD...: runs it under the time limit `limit` (seconds); sets rc
# (the exit code, or "timeout") and secs; stdout and stderr go to $out
# and $err.
timed() {
    local t0 t1
    t0=$(now)
    rc=0
    # (the braces keep the shell's own "Aborted" line for a crash off the terminal)
    { timeout --kill-after=10 "$limit" "$@" >"$out" 2>"$err" </dev/null; } 2>/dev/null || rc=$?
    t1=$(now)
    secs=$(elapsed "$t0" "$t1")
    # 124: the limit was hit; 137 (SIGKILL) after the limit: did not stop in time.
    if [ "$rc" -eq 124 ] || { [ "$rc" -eq 137 ] && awk -v s="$secs" -v l="$limit" 'BEGIN { exit !(s >= l) }'; }; then
        rc=timeout
    fi
}

# timed_runs N CMD...: `timed` up to N times in a row; secs is the median
# of the wall times (N even: the mean of the two middle ones). The repeats
# stop at a run that timed out or whose exit code differs from the first
# run's: rc and the outputs left are always those of the last run. One run
# of a few tenths of a second moves by 10% or more from one run to the next
# on a shared machine; the median of three is steadier.
timed_runs() {
    local n=$1 first_rc k
    shift
    local times=()
    timed "$@"
    first_rc=$rc
    times+=("$secs")
    for ((k = 1; k < n; k++)); do
        # (rc may be the word "timeout": compared as strings)
        if [ "$rc" = timeout ] || [ "$rc" != "$first_rc" ]; then break; fi
        timed "$@"
        times+=("$secs")
    done
    secs=$(printf '%s\n' "${times[@]}" | sort -g | awk '{ v[NR] = $1 }
        END { if (NR % 2) printf "%.3f", v[(NR + 1) / 2]; else printf "%.3f", (v[NR / 2] + v[NR / 2 + 1]) / 2 }')
}

# check_repeat SCRIPT: `repeat` must be a whole number, at least 1.
check_repeat() {
    case $repeat in ''|*[!0-9]*|0) echo "$1: --repeat needs a whole number (at least 1)" >&2; exit 1 ;; esac
}
