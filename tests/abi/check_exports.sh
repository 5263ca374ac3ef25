#!/bin/sh
# ABI check of the built shared library:
#   check_exports.sh <libcbr.so> <cbr.h> <expected soname>
#
#  1. every dynamic symbol libcbr exports is a function named cbr_* that is
#     declared in cbr.h: no C++ symbol, no dependency's symbol, no data, no
#     undeclared function leaks into the ABI;
#  2. every function declared CBR_API in cbr.h is exported as a function;
#  3. the soname is the expected one (libcbr.so.<major>).
# Prints every problem found, exits 1 if there is one.
set -eu

if [ $# -ne 3 ]; then
    echo "usage: $0 <libcbr.so> <cbr.h> <expected soname>" >&2
    exit 2
fi
lib=$1
header=$2
expected_soname=$3
here=$(cd "$(dirname "$0")" && pwd)

for tool in nm readelf; do
    command -v "$tool" >/dev/null 2>&1 || { echo "SKIP: $tool not found"; exit 77; }
done
[ -r "$lib" ] || { echo "FAIL: cannot read $lib"; exit 1; }

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

sh "$here/list_header_api.sh" functions "$header" | sort -u > "$tmp/declared"
if [ ! -s "$tmp/declared" ]; then
    fail "found no CBR_API declaration in $header (parser broken?)"
fi

# "value type name" lines of the defined dynamic symbols; symbol versions
# (name@@VERSION) are cut off.
nm -D --defined-only "$lib" | awk 'NF >= 2 { name = $NF; sub(/@.*/, "", name); print $(NF - 1), name }' > "$tmp/symbols"

# Symbols the linker defines in every shared object, and the absolute
# symbols that name version nodes of a version script: not part of the API.
awk '$1 != "A" && $2 != "_init" && $2 != "_fini" && $2 != "_edata" &&
     $2 != "_end" && $2 != "__bss_start"' "$tmp/symbols" > "$tmp/api_symbols"

# T/t: code, W/w: weak code, i: indirect function. Anything else is data.
awk '$1 ~ /^[TtWwi]$/ { print $2 }' "$tmp/api_symbols" | sort -u > "$tmp/functions"
awk '$1 !~ /^[TtWwi]$/ { print $1, $2 }' "$tmp/api_symbols" > "$tmp/data"

while read -r type name; do
    fail "exported data symbol '$name' (nm type $type): libcbr must export functions only"
done < "$tmp/data"

while read -r name; do
    case $name in
    cbr_*) grep -qx "$name" "$tmp/declared" ||
           fail "exported function '$name' is not declared in cbr.h (hide it or declare it)" ;;
    *) fail "exported function '$name' does not start with cbr_ (a leaked internal or dependency symbol)" ;;
    esac
done < "$tmp/functions"

while read -r name; do
    grep -qx "$name" "$tmp/functions" ||
        fail "'$name' is declared CBR_API in cbr.h but libcbr does not export it"
done < "$tmp/declared"

soname=$(readelf -d "$lib" | sed -n 's/.*(SONAME).*\[\(.*\)\].*/\1/p')
if [ "$soname" != "$expected_soname" ]; then
    fail "soname is '${soname:-<none>}', expected '$expected_soname'"
fi

if [ "$failures" -ne 0 ]; then
    echo "$failures problem(s) in the exported ABI of $lib"
    exit 1
fi
echo "OK: $lib exports exactly the $(wc -l < "$tmp/declared") functions of cbr.h, soname $soname"
