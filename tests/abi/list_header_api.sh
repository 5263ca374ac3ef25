#!/bin/sh
# Lists the public API declared in cbr.h, one item per line:
#   list_header_api.sh functions <cbr.h>   names of the CBR_API functions
#   list_header_api.sh constants <cbr.h>   "NAME VALUE" of every
#                                          #define CBR_* constant
# Comments are stripped first, so prose that mentions CBR_API is ignored.
# Used by check_exports.sh and check_fortran_binding.sh.
set -eu

if [ $# -ne 2 ]; then
    echo "usage: $0 functions|constants <cbr.h>" >&2
    exit 2
fi
what=$1
header=$2
[ -r "$header" ] || { echo "$0: cannot read $header" >&2; exit 2; }

# Removes /* ... */ (also across lines) and // comments.
strip_comments() {
    awk '
    {
        line = $0; out = ""
        while (length(line) > 0) {
            if (in_comment) {
                i = index(line, "*/")
                if (i == 0) { line = "" } else { line = substr(line, i + 2); in_comment = 0 }
            } else {
                i = index(line, "/*")
                j = index(line, "//")
                if (j > 0 && (i == 0 || j < i)) { out = out substr(line, 1, j - 1); line = "" }
                else if (i == 0) { out = out line; line = "" }
                else { out = out substr(line, 1, i - 1) " "; line = substr(line, i + 2); in_comment = 1 }
            }
        }
        print out
    }' "$1"
}

case $what in
functions)
    # A declaration starts with CBR_API at the beginning of a line and ends
    # at the next ";" (it may span lines). The name is the identifier just
    # before the first "(".
    strip_comments "$header" | awk '
    collecting || /^[ \t]*CBR_API[ \t]/ {
        buf = buf " " $0; collecting = 1
        if (index($0, ";") > 0) {
            sub(/\(.*/, "", buf)
            if (match(buf, /[A-Za-z_][A-Za-z_0-9]*[ \t]*$/)) {
                name = substr(buf, RSTART, RLENGTH); gsub(/[ \t]/, "", name)
                print name
            }
            buf = ""; collecting = 0
        }
    }'
    ;;
constants)
    # Every object-like #define CBR_* with a value, except the include guard
    # and the export macro. Parentheses and blanks are dropped from the value.
    strip_comments "$header" \
        | sed -n 's/^[[:blank:]]*#[[:blank:]]*define[[:blank:]]\{1,\}\(CBR_[A-Za-z0-9_]*\)[[:blank:]]\{1,\}\(.*[^[:blank:]]\)[[:blank:]]*$/\1 \2/p' \
        | awk '$1 != "CBR_API" && $1 != "CBR_H" {
                   name = $1; $1 = ""; value = $0; gsub(/[() \t]/, "", value)
                   print name, value
               }'
    ;;
*)
    echo "$0: unknown list '$what'" >&2
    exit 2
    ;;
esac
