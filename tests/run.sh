#!/bin/sh
# Runs every test binary of each build flavour given (build dirs), plus the
# command-line tests tests/cli_*.sh against that flavour's shadesim, and
# prints the closing line "N passed, N failed[, N skipped]".
# Each test prints one line: "ok NAME", "FAIL NAME" or "skip NAME: why";
# a test program that crashes or exits non-zero without a FAIL line counts
# as one failure of its own.
#
# TST_JOBS tests run at a time (default 2: the suite's CPU time is spread
# over two cores); each one's output is kept and printed, as one block
# under its name, as soon as it finishes, so a long suite shows progress
# from its first minute; the blocks come in the order the tests finish.
# The closing count does not depend on that order. TST_JOBS=1 runs them
# one by one (then in the fixed order: the slow sanitizer flavour first,
# then the others' scripts, then their binaries).
cd "$(dirname "$0")/.." || exit 2
jobs=${TST_JOBS:-2}
case $jobs in ''|*[!0-9]*|0) echo "tests/run.sh: TST_JOBS must be a whole number >= 1" >&2; exit 2;; esac
dir=$(mktemp -d) || exit 2
trap 'rm -rf "$dir"' EXIT
trap 'exit 130' INT TERM

# python3 behind a version manager's shim (pyenv's is a shell script that
# looks the version up) starts in half a second of CPU instead of a
# twentieth, and the tests start it about a hundred times: they get the
# interpreter the shim picks, found once here, first on their PATH.
if py=$(python3 -c 'import sys; print(sys.executable)' 2>/dev/null) && [ -x "$py" ] &&
   [ "$py" != "$(command -v python3)" ]; then
    mkdir "$dir/bin" && ln -s "$py" "$dir/bin/python3" && PATH=$dir/bin:$PATH && export PATH
fi

# TST_QUICK=1 (make test-quick), the edit loop's suite: the C tests but
# those tests/slow.list names, and the command-line scripts
# tests/quick.list names (a sample), under 30 s on an idle 2-core machine.
slow= quick=
if [ "${TST_QUICK:-0}" = 1 ]; then slow=$(sed 's/#.*//' tests/slow.list); quick=$(sed 's/#.*//' tests/quick.list); fi
# tests/long.list names the tests only `make test-long` runs (TST_LONG=1:
# those alone); every other run leaves them out.
long=$(sed 's/#.*//' tests/long.list)
in_list() { x=$1; shift; for y in "$@"; do [ "$x" = "$y" ] && return 0; done; return 1; }
is_slow() {
    if [ "${TST_LONG:-0}" = 1 ]; then in_list "$1" $long && return 1; return 0; fi
    in_list "$1" $slow $long
}

# The job list: one line "N BUILD KIND PATH" per test, in print order.
n=0
for b in "$@"; do
    for t in "$b"/tests/test_*; do
        is_slow "$(basename "$t")" && continue
        [ -x "$t" ] && { n=$((n + 1)); echo "$n $b bin $t"; }
    done
    for t in tests/cli_*.sh; do
        is_slow "$(basename "$t" .sh)" && continue
        [ "${TST_QUICK:-0}" = 1 ] && ! in_list "$(basename "$t" .sh)" $quick && continue
        # the portable flavour (no vector loops, switch dispatch): the
        # batch's and the kernel's tests only
        case $b in *-portable) case $t in tests/cli_engine.sh|tests/cli_gold.sh) ;; *) continue ;; esac ;; esac
        [ -f "$t" ] && { n=$((n + 1)); echo "$n $b cli $t"; }
    done
done >"$dir/jobs"

# One job: its output to N.out, its exit status to N.rc, then its job line
# into the fifo the printer below reads (written last: the printer prints
# a job the moment its line comes, without polling for it).
cat >"$dir/one.sh" <<'EOF'
d=$1 i=$2 b=$3 kind=$4 t=$5
export SHADESIM="$b/shadesim" TST_BUILD="$b"
# Under the sanitizers, freed blocks held back 32 MB deep instead of 256:
# a use after free is caught while the block is among the last 32 MB freed
# (the use right after a free, as before); each fresh block was a fresh page,
# and the page faults (two to four times as many: test_cells 207,000 against
# 68,000) were a third of a sanitized test's CPU. Options given in
# ASAN_OPTIONS come after, and win.
case $b in *-asan) export ASAN_OPTIONS="quarantine_size_mb=32${ASAN_OPTIONS:+:$ASAN_OPTIONS}" ;; esac
# TST_TIMES=FILE: each test's wall, user and system seconds appended there
# (GNU time's -a -o), to find what the suite's time goes to.
if [ -n "${TST_TIMES:-}" ]; then set -- /usr/bin/time -a -o "$TST_TIMES" -f "%e %U %S $b $t"; else set --; fi
if [ "$kind" = bin ]; then "$@" "$t" >"$d/$i.out" 2>&1; else "$@" sh "$t" >"$d/$i.out" 2>&1; fi
echo $? >"$d/$i.tmp" && mv "$d/$i.tmp" "$d/$i.rc"
echo "$i $b $kind $t" >"$d/fifo"
EOF
# The printer, in the background: each job's block as soon as it is done,
# in the order they finish, from the job lines the jobs write into a fifo
# (a blocking read: a suite of three hundred seconds used to cost ten of
# CPU in a loop polling the jobs' files). The runner holds the fifo open
# for reading and writing (fd 3), so a job's write never waits for the
# printer, and ends it with "done" once every job has returned. (The jobs
# themselves run in the foreground: a background command of a script
# ignores SIGINT, and so would every test it runs, which test_out checks.)
print_one() {
    i=$1 b=$2 kind=$3 t=$4
    name=$t
    [ "$kind" = cli ] && name="$t [$b]"
    echo "== $name"
    if [ -f "$dir/$i.rc" ]; then
        rc=$(cat "$dir/$i.rc")
        sed 's|^|  |' "$dir/$i.out"
        cat "$dir/$i.out" >>"$dir/log"
    else
        rc="none (not run: the runner stopped)"
    fi
    if [ "$rc" != 0 ] && ! grep -q '^FAIL ' "$dir/$i.out" 2>/dev/null; then
        echo "FAIL $name: exit status $rc" | tee -a "$dir/log"
    fi
    : >"$dir/$i.shown"
}
print_all() {
    : >"$dir/log"
    left=$(wc -l <"$dir/jobs")
    while [ "$left" -gt 0 ] && read -r i b kind t <&3; do
        if [ "$i" = done ]; then
            # the runner stopped early (xargs after a killed job): the
            # jobs never printed never ran, and count as failures
            while read -r i b kind t; do
                [ -f "$dir/$i.shown" ] || print_one "$i" "$b" "$kind" "$t"
            done <"$dir/jobs"
            return
        fi
        print_one "$i" "$b" "$kind" "$t"
        left=$((left - 1))
    done
}
mkfifo "$dir/fifo" && exec 3<>"$dir/fifo" || exit 2
print_all &
printer=$!

# Longest first: the ASan flavour's jobs (slower) lead, then the other
# flavours' scripts (seconds each: a process per check) before their test
# programs (most well under a second), so that the workers finish close
# together.
{ grep -- '-asan ' "$dir/jobs"; grep -v -- '-asan ' "$dir/jobs" | grep ' cli '; grep -v -- '-asan ' "$dir/jobs" | grep -v ' cli '; } \
    | awk -v d="$dir" '{ print d, $1, $2, $3, $4 }' \
    | xargs -n 5 -P "$jobs" sh "$dir/one.sh" 3>&-
echo done >&3
wait "$printer"

log=$dir/log
pass=$(grep -c '^ok ' "$log")
fail=$(grep -c '^FAIL ' "$log")
skip=$(grep -c '^skip ' "$log")
if [ "$fail" -gt 0 ]; then echo "failed tests:"; grep '^FAIL ' "$log" | sed 's/^/  /'; fi
if [ "$skip" -gt 0 ]; then
    echo "$pass passed, $fail failed, $skip skipped"
else
    echo "$pass passed, $fail failed"
fi
[ "$fail" -eq 0 ] && [ "$pass" -gt 0 ]
