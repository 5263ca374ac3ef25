#!/usr/bin/env bash
# Mesh generation benchmark: libcbr (`cbr mesh`, boundary recovery then
# full mesh generation, Du & Wang 2004 section 6) against TetGen 1.5
# (`tetgen -pYq1.414`, the Debian package: surface kept, radius-edge bound
# 1.414), and with --gmsh against Gmsh's 3D Delaunay too, on the same
# surfaces, one after the other in the same run. All meshes are measured by
# the same code (refine_bench_table.py, the formulas of
# src/cli/quality.hpp) and printed per mesh and in total: tetrahedra,
# average and minimum quality q = 3 r_in / r_circ, minimum dihedral angle,
# % of tetrahedra with q < 0.1, wall time, and the ratios libcbr / peer;
# for libcbr also Table II's "q < 0.1 touching a Steiner point" (from its
# --json report: the peers' outputs do not say which points are Steiner
# points).
#
#   tests/bench/run_refine_bench.sh [options] [DATA_DIR] [SURFACE...]
#
#   DATA_DIR      directory of .off surfaces (default $CBR_SHARED_DATA_DIR/surfaces,
#                 else <repo>/../shared/data/surfaces)
#   SURFACE...    only these surfaces: paths, or names in DATA_DIR with or
#                 without .off (default: every *.off in DATA_DIR; surfaces
#                 that cbr cannot recover yet are reported as FAILED)
#   --size H      pass --size H to cbr mesh (TetGen gets -a with the volume
#                 of a regular tetrahedron of edge H)
#   --growth R    pass --growth R to cbr mesh (the size grows by R per unit
#                 length away from the surface; TetGen gets nothing more)
#   --csv FILE    also write the table (per mesh, then the totals) as CSV
#   --timeout S   seconds allowed to each run (default $CBR_BENCH_TIMEOUT or 300)
#   --repeat N    run each tool N times on each surface, one run after the
#                 other, and report the median wall time (default
#                 $CBR_BENCH_REPEAT or 1; every run makes the same mesh)
#   --threads N   pass --threads N to cbr (1: libcbr on one thread, as the
#                 peers run; default: cbr's own, as many as the hardware
#                 runs at once; the meshes are the same either way)
#   --gmsh        also run gmsh (`gmsh -3`, Mesh.Algorithm3D = 1: Delaunay;
#                 the surface given as one discrete surface bounding one
#                 volume, off_to_medit.py) and print a second table, cbr
#                 against gmsh; installs the Debian package gmsh when it is
#                 missing. Gmsh 4.8 takes minutes on the largest surfaces
#                 (mind --timeout); its meshes are not checked here, and
#                 its Medit writer rounds coordinates to 14 significant
#                 digits (points given with 16 or 17 come back moved in
#                 their last digits)
#   --keep        keep the outputs (the work directory is printed)
#
# Build directory of libcbr and `cbr` (Release): $CBR_BENCH_BUILD (default
# <repo>/build-bench/refine). Extra CMake arguments: $CBR_BENCH_CMAKE_ARGS.
# Installs the Debian package tetgen when it is missing (and says so).
#
# Exit status: 0 when the benchmark ran (whatever each mesh did), 1 on a
# bad command line or a failed build.
set -eu

here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)
# shellcheck source=bench_common.sh
. "$here/bench_common.sh"
build=${CBR_BENCH_BUILD:-$repo/build-bench/refine}
jobs=$(nproc 2>/dev/null || echo 2)
extra=${CBR_BENCH_CMAKE_ARGS:-}
limit=${CBR_BENCH_TIMEOUT:-300}
repeat=${CBR_BENCH_REPEAT:-1}
thread_args=()
data=
csv=
keep=0
gmsh=0
size=
growth=
surfaces=()

usage() {
    sed -n '2,/^set -eu/p' "$0" | sed -e '/^set -eu/d' -e 's/^# \{0,1\}//' >&2
    exit 1
}

while [ $# -gt 0 ]; do
    case $1 in
        --csv) [ $# -ge 2 ] || usage; csv=$2; shift 2 ;;
        --csv=*) csv=${1#--csv=}; shift ;;
        --size) [ $# -ge 2 ] || usage; size=$2; shift 2 ;;
        --size=*) size=${1#--size=}; shift ;;
        --growth) [ $# -ge 2 ] || usage; growth=$2; shift 2 ;;
        --growth=*) growth=${1#--growth=}; shift ;;
        --threads) [ $# -ge 2 ] || usage; thread_args=(--threads "$2"); shift 2 ;;
        --threads=*) thread_args=(--threads "${1#--threads=}"); shift ;;
        --timeout) [ $# -ge 2 ] || usage; limit=$2; shift 2 ;;
        --timeout=*) limit=${1#--timeout=}; shift ;;
        --repeat) [ $# -ge 2 ] || usage; repeat=$2; shift 2 ;;
        --repeat=*) repeat=${1#--repeat=}; shift ;;
        --keep) keep=1; shift ;;
        --gmsh) gmsh=1; shift ;;
        -h|--help) usage ;;
        --) shift; break ;;
        -*) echo "run_refine_bench.sh: unknown option '$1'" >&2; usage ;;
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
case $limit in ''|*[!0-9]*|0) echo "run_refine_bench.sh: --timeout needs whole seconds (at least 1)" >&2; exit 1 ;; esac
check_repeat run_refine_bench.sh
if [ -n "$size" ] && ! awk -v s="$size" 'BEGIN { exit !(s + 0 > 0) }'; then
    echo "run_refine_bench.sh: --size needs a length > 0" >&2
    exit 1
fi

bench_surfaces run_refine_bench.sh "$data" "${surfaces[@]}"
bench_build_cbr run_refine_bench.sh

as_root() {
    if [ "$(id -u)" -eq 0 ]; then "$@"; elif command -v sudo >/dev/null 2>&1; then sudo "$@"; else return 1; fi
}
have_tetgen=1
if ! command -v tetgen >/dev/null 2>&1; then
    echo "== tetgen is missing: installing the Debian package tetgen (apt-get install -y tetgen)"
    as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y tetgen >/dev/null 2>&1 || true
    command -v tetgen >/dev/null 2>&1 || { echo "   could not install tetgen: its columns stay empty" >&2; have_tetgen=0; }
fi

if [ "$gmsh" -eq 1 ] && ! command -v gmsh >/dev/null 2>&1; then
    echo "== gmsh is missing: installing the Debian package gmsh (apt-get install -y gmsh)"
    as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y gmsh >/dev/null 2>&1 || true
    command -v gmsh >/dev/null 2>&1 || { echo "   could not install gmsh: no gmsh table" >&2; gmsh=0; }
fi

bench_workdir refine

size_args=()
tg_area=
if [ -n "$size" ]; then
    size_args=(--size "$size")
    tg_area=$(awk -v h="$size" 'BEGIN { printf "a%.17g", h * h * h / 8.48528137423857 }')
fi

raw=$work/raw.csv
echo "file,cbr_status,cbr_seconds,cbr_node,cbr_ele,tetgen_status,tetgen_seconds,tetgen_node,tetgen_ele,cbr_json,gmsh_status,gmsh_seconds,gmsh_mesh" >"$raw"
n=${#files[@]}
i=0
if [ -n "$growth" ]; then size_args+=(--growth "$growth"); fi
[ "$repeat" -gt 1 ] && runs=", median of $repeat runs" || runs=
echo "== run: ${n} surfaces, ${limit} s limit per run${runs}${size:+, --size $size}${growth:+, --growth $growth}"
for f in "${files[@]}"; do
    i=$((i + 1))
    name=$(basename "$f" .off)
    dir=$work/$name
    mkdir -p "$dir/tetgen"

    out=$dir/cbr.out err=$dir/cbr.err
    timed_runs "$repeat" "$cbr" mesh -q "$f" -o "$dir/cbr.node" --json "$dir/cbr.json" "${size_args[@]}" "${thread_args[@]}"
    case $rc in
        0) cbr_status=ok ;;
        3) cbr_status=FAILED ;;
        timeout) cbr_status=TIMEOUT ;;
        *) cbr_status=ERROR ;;
    esac
    cbr_secs=$secs

    tg_status='' tg_secs=''
    if [ "$have_tetgen" -eq 1 ]; then
        cp "$f" "$dir/tetgen/$name.off"
        out=$dir/tetgen.out err=$dir/tetgen.err
        timed_runs "$repeat" tetgen "-pYq1.414${tg_area}Q" "$dir/tetgen/$name.off"
        tg_secs=$secs
        if [ "$rc" = timeout ]; then
            tg_status=TIMEOUT
        elif [ "$rc" -eq 0 ] && [ -s "$dir/tetgen/$name.1.ele" ]; then
            tg_status=ok
        else
            tg_status=FAILED
        fi
    fi
    gm_status='' gm_secs=''
    if [ "$gmsh" -eq 1 ]; then
        mkdir -p "$dir/gmsh"
        python3 "$here/off_to_medit.py" "$f" "$dir/gmsh/surface.mesh"
        # Every surface of the file bounds the one volume; the size field
        # comes from the surface's edges (gmsh's default).
        printf 'Merge "surface.mesh";\nSurface Loop(1) = Surface{:};\nVolume(1) = {1};\nMesh.Algorithm3D = 1;\n' \
            >"$dir/gmsh/volume.geo"
        out=$dir/gmsh.out err=$dir/gmsh.err
        timed_runs "$repeat" gmsh -3 "$dir/gmsh/volume.geo" -o "$dir/gmsh/volume.mesh" -format mesh -v 2
        gm_secs=$secs
        if [ "$rc" = timeout ]; then
            gm_status=TIMEOUT
        elif [ "$rc" -eq 0 ] && grep -q '^ *Tetrahedra' "$dir/gmsh/volume.mesh" 2>/dev/null; then
            gm_status=ok
        else
            gm_status=FAILED
        fi
    fi
    echo "$name,$cbr_status,$cbr_secs,$dir/cbr.node,$dir/cbr.ele,$tg_status,$tg_secs,$dir/tetgen/$name.1.node,$dir/tetgen/$name.1.ele,$dir/cbr.json,$gm_status,$gm_secs,$dir/gmsh/volume.mesh" >>"$raw"
    printf '   [%d/%d] %-36s cbr %-7s %8s s   tetgen %-7s %8s s%s\n' "$i" "$n" "$name" "$cbr_status" "$cbr_secs" \
        "${tg_status:-n/a}" "${tg_secs:--}" "${gm_status:+   gmsh $gm_status $gm_secs s}"
done

echo
python3 "$here/refine_bench_table.py" "$raw" ${csv:+--csv "$csv"}
