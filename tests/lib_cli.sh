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

# The build flavour under test (tests/run.sh sets TST_BUILD): ASAN=1 under
# the sanitizers, where each process starts in about 0.1 s of CPU and runs
# 3 to 5 times slower. A test whose loops repeat one code path over every
# unit, schedule or variant walks a part of them there (what it leaves to
# the plain build, it says); its checks are the same.
case "${TST_BUILD:-}" in *-asan) ASAN=1 ;; *) ASAN= ;; esac

# no_leak_check: under the sanitizers, no leak check at each shadesim
# process's exit (a third of a sanitized process's start-up and exit
# time). For the tests that run the same verbs over and over (every unit,
# every variant); the verbs' leaks, error paths included, are checked by
# cli_run, cli_files, cli_strict, cli_outset, cli_sweep, cli_scene,
# cli_netlist, cli_verilog, cli_stability and the test programs.
no_leak_check() {
    [ -n "$ASAN" ] && export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0"
    return 0
}

# full_only: true in make test, false in make test-quick (TST_QUICK=1,
# the edit loop's subset): a test's slow parts that repeat a verb another
# quick check runs are left to make test (each says what it leaves).
full_only() { [ "${TST_QUICK:-0}" != 1 ]; }

# plain_only: the rest of the test checks what no build flavour changes
# (the sources, the docs): it runs in the plain build alone.
plain_only() {
    case "${TST_BUILD:-}" in
    *-asan|*-portable) echo "skip ${PREFIX%.}: checks no build flavour changes, run in the plain build"; exit 0 ;;
    esac
}

# run_full TEST CHECK VAR: a test program of the plain build run with VAR=1
# (its whole table or matrix, for make test-long); one line CHECK, ok when
# it exits 0 with no FAIL line, else its first lines that are not ok.
run_full() {
    prog=${TST_BUILD:-build}/tests/$1
    case ${TST_BUILD:-build} in
    *-asan) echo "skip ${PREFIX%.}: the plain build runs the whole table"; return 0 ;;
    esac
    if [ ! -x "$prog" ]; then fail "$2" "no $prog"; return 0; fi
    env "$3=1" "$prog" >"$T/out" 2>&1; rc=$?
    if [ "$rc" -eq 0 ] && ! grep -q '^FAIL' "$T/out"; then ok "$2"
    else fail "$2" "$(grep -v '^ok' "$T/out" | head -12 | tr '\n' ' ')"; fi
}

# units_and_schedules: a line "UNIT: SCHED SCHED ..." a unit, from list.
units_and_schedules() {
    "$S" list | awk '/^[a-z0-9_]+ —/ { u = $1 }
        /^  schedules:/ { sub(/^  schedules: /, ""); n = split($0, a, /\), /); s = "";
                          for (i = 1; i <= n; i++) { split(a[i], b, " "); s = s " " b[1] } print u ":" s }'
}
