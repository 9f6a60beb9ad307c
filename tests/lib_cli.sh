# lib_cli.sh - what the command-line tests share; sourced, not run.
# Sets S (the shadesim under test) and T (a scratch folder removed on exit),
# and the helpers that print the one line per check tests/run.sh counts:
# "ok NAME", "FAIL NAME: why". PREFIX (e.g. "cli_run.") goes before names.
S=${SHADESIM:-bin/shadesim}
T=$(mktemp -d /tmp/shadesim_cli.XXXXXX) || exit 1
trap 'rm -rf "$T"' EXIT
export SHADESIM_HOME=${SHADESIM_HOME:-$(pwd)}

ok()    { echo "ok ${PREFIX}$1"; }
fail()  { if [ -n "$2" ]; then echo "FAIL ${PREFIX}$1: $2"; else echo "FAIL ${PREFIX}$1"; fi; }
check() { name=$1; shift; if "$@"; then ok "$name"; else fail "$name"; fi; }

# expect NAME STATUS CMD...: CMD's exit status is STATUS (stdout in $T/out,
# stderr in $T/err), and for status 2 stderr is exactly one line starting
# "shadesim: ".
expect() {
    name=$1; want=$2; shift 2
    "$@" >"$T/out" 2>"$T/err"; got=$?
    if [ "$got" -ne "$want" ]; then fail "$name" "exit $got, expected $want: $(head -c 300 "$T/err")"; return 1; fi
    if [ "$want" -eq 2 ]; then
        n=$(wc -l <"$T/err")
        if [ "$n" -ne 1 ] || ! grep -q '^shadesim: ' "$T/err"; then fail "$name" "stderr not one 'shadesim:' line: $(cat "$T/err")"; return 1; fi
    fi
    ok "$name"
}
