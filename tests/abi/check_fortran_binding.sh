#!/bin/sh
# The Fortran module must follow cbr.h:
#   check_fortran_binding.sh <cbr.h> <cbr.f90>
# Every CBR_API function of the header has a bind(C, name="...") interface
# in the module, every bind(C) name of the module (except strlen, used by
# cbr_f_string) is a function of the header, and every #define CBR_* constant
# is an integer(c_int), parameter of the same name and the same value.
set -eu

if [ $# -ne 2 ]; then
    echo "usage: $0 <cbr.h> <cbr.f90>" >&2
    exit 2
fi
header=$1
module=$2
here=$(cd "$(dirname "$0")" && pwd)
[ -r "$module" ] || { echo "FAIL: cannot read $module"; exit 1; }

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

sh "$here/list_header_api.sh" functions "$header" | sort -u > "$tmp/declared"
sh "$here/list_header_api.sh" constants "$header" > "$tmp/constants"
[ -s "$tmp/declared" ] || fail "found no CBR_API declaration in $header (parser broken?)"
[ -s "$tmp/constants" ] || fail "found no #define CBR_* constant in $header (parser broken?)"

# Fortran is case-insensitive and free-form; drop "!" comments first.
sed 's/!.*//' "$module" > "$tmp/code"

sed -n 's/.*[bB][iI][nN][dD][[:blank:]]*([[:blank:]]*[cC][[:blank:]]*,[[:blank:]]*[nN][aA][mM][eE][[:blank:]]*=[[:blank:]]*["'"'"']\([A-Za-z_0-9]*\)["'"'"'].*/\1/p' \
    "$tmp/code" | sort -u > "$tmp/bound"

while read -r name; do
    grep -qx "$name" "$tmp/bound" || fail "cbr.h function '$name' has no bind(C, name=\"$name\") interface in the Fortran module"
done < "$tmp/declared"
while read -r name; do
    [ "$name" = strlen ] && continue
    grep -qx "$name" "$tmp/declared" || fail "the Fortran module binds '$name', which cbr.h does not declare"
done < "$tmp/bound"

while read -r name value; do
    # integer(c_int), parameter[, public] :: NAME = VALUE
    found=$(grep -i "integer[[:blank:]]*([[:blank:]]*c_int[[:blank:]]*)[[:blank:]]*,[[:blank:]]*parameter.*::[[:blank:]]*${name}[[:blank:]]*=" "$tmp/code" \
            | sed 's/.*=[[:blank:]]*//; s/[[:blank:]]//g' | head -n 1)
    if [ -z "$found" ]; then
        fail "constant $name = $value of cbr.h is missing from the Fortran module (integer(c_int), parameter)"
    elif [ "$found" != "$value" ]; then
        fail "constant $name is $value in cbr.h but $found in the Fortran module"
    fi
done < "$tmp/constants"

if [ "$failures" -ne 0 ]; then
    echo "$failures difference(s) between $header and $module"
    exit 1
fi
echo "OK: $module binds the $(wc -l < "$tmp/declared") functions and $(wc -l < "$tmp/constants") constants of cbr.h"
