#!/bin/sh
# cli_size.sh - product code stays readable in pieces: no .c or .h file of
# the layers over 800 lines, no function over 120 lines of body. A function
# is what starts at column 0 with a name and "(" and has its body between a
# "{" (alone at column 0, or ending the signature's last line) and the next
# "}" at column 0, which is how every function here is written. The checker
# is first run on planted files, so this test shows it can fail.
. tests/lib_cli.sh
PREFIX=cli_size.

MAX_LINES=800
MAX_BODY=120

# too_big DIR...: "FILE: N lines" and "FILE:LINE: NAME: N lines of body",
# file by file in sorted order; one awk over every file (a wc and an awk
# per file were most of this test's time).
too_big() {
    find "$@" \( -name '*.c' -o -name '*.h' \) -type f | sort >"$T/files"
    [ -s "$T/files" ] || return 0
    xargs awk -v MAX="$MAX_BODY" -v MAXL="$MAX_LINES" '
        function flush() {
            if (F != "") { if (n > MAXL) printf "%s: %d lines (limit %d)\n", F, n, MAXL; printf "%s", buf }
        }
        FNR == 1 { flush(); F = FILENAME; n = 0; buf = ""; open = 0 }
        { n++ }
        /^[A-Za-z_].*\(/ { sig = $0; sigline = FNR }
        /^\{[ \t]*$/ || (/^[A-Za-z_].*\)[ \t]*\{[ \t]*$/) { if (!open) { open = FNR; name = sig; at = sigline } next }
        /^\}/ && open {
            body = FNR - open - 1
            if (body > MAX) {
                sub(/\(.*/, "", name)
                buf = buf sprintf("%s:%d: %s: %d lines of body (limit %d)\n", F, at, name, body, MAX)
            }
            open = 0
        }
        END { flush() }' <"$T/files"
}

# 1. The checker finds what it should, and nothing else.
P=$T/plant
mkdir -p "$P"
{ echo 'static int long_one(int x)'; echo '{'; i=0; while [ $i -lt 121 ]; do echo '    x++;'; i=$((i + 1)); done
  echo '}'
  echo 'int fits(int x) {'; i=0; while [ $i -lt 120 ]; do echo '    x++;'; i=$((i + 1)); done; echo '}'; } >"$P/f.c"
i=0; while [ $i -lt 801 ]; do echo "/* $i */"; i=$((i + 1)); done >"$P/big.h"
got=$(too_big "$P")
want="$P/big.h: 801 lines (limit $MAX_LINES)
$P/f.c:1: static int long_one: 121 lines of body (limit $MAX_BODY)"
[ "$got" = "$want" ] && ok checker_finds_planted || fail checker_finds_planted "$(echo "$got" | tr '\n' '|')"

# 2. The product code.
hits=$(too_big sim base chart vectors units scene testbench)
check product_code_within_limits [ -z "$hits" ]
[ -n "$hits" ] && echo "$hits" | sed 's/^/  /'
exit 0
