#!/bin/sh
# Output files and stdout from the command line: device nodes, FIFOs and
# symbolic links given as outputs are written through (never replaced),
# "-" is stdout, write errors (stdout too) are exit 2 with one line, the
# umask is respected, merge refuses junk as it reads, and a run killed by
# a signal leaves no temporary behind. Devices are opened, never created
# in /dev; a copy of /dev/null's node is made in the scratch folder when
# the test may (root), which is the case where replacing it did damage.
PREFIX=cli_files.
. tests/lib_cli.sh
case $S in /*) ;; */*) S=$(pwd)/$S ;; esac    # some checks run in another folder

# expect2 NAME CMD...: exit 2 with exactly one "shadesim: " line on stderr.
expect2() {
    name=$1; shift
    "$@" >"$T/out" 2>"$T/err"; got=$?
    if [ "$got" -ne 2 ]; then fail "$name" "exit $got, expected 2: $(head -c 300 "$T/err")"; return; fi
    if [ "$(wc -l <"$T/err")" -ne 1 ] || ! grep -q '^shadesim: ' "$T/err"; then
        fail "$name" "stderr not one 'shadesim:' line: $(head -c 300 "$T/err")"; return
    fi
    ok "$name"
}
# no_temp NAME DIR: no temporary (".tmp-" in a name) left in DIR.
no_temp() {
    if ls -a "$2" | grep -q '\.tmp-'; then fail "$1" "left: $(ls -a "$2" | grep '\.tmp-' | head -3)"; else ok "$1"; fi
}

# --- character devices: written through, still devices afterwards -------
"$S" vectors horner3 -o /dev/null; rc=$?
if [ $rc -eq 0 ] && [ -c /dev/null ]; then ok vectors_devnull; else fail vectors_devnull "exit $rc, /dev/null: $(ls -l /dev/null)"; fi
"$S" run horner3 --out /dev/null --vcd /dev/null >/dev/null; rc=$?
if [ $rc -eq 0 ] && [ -c /dev/null ] && [ ! -e /dev/null.gtkw ]; then ok run_out_vcd_devnull
else fail run_out_vcd_devnull "exit $rc, $(ls -l /dev/null /dev/null.gtkw 2>&1)"; fi
# A node of our own (root only): the case where the old code replaced it.
if mknod "$T/null" c 1 3 2>/dev/null; then
    "$S" vectors horner3 -o "$T/null" && "$S" run horner3 --out "$T/null" --vcd "$T/null" >/dev/null
    rc=$?
    if [ $rc -eq 0 ] && [ -c "$T/null" ]; then ok own_null_node; else fail own_null_node "exit $rc, $(ls -l "$T/null")"; fi
    rm -f "$T/null"
else
    echo "skip ${PREFIX}own_null_node: mknod not permitted (not root)"
fi

# --- /dev/full: ENOSPC is exit 2, said as such, for files and stdout -----
if [ -c /dev/full ]; then
    expect2 run_out_devfull "$S" run horner3 --out /dev/full
    grep -q 'No space left on device' "$T/err" && ok devfull_says_no_space || fail devfull_says_no_space "$(cat "$T/err")"
    expect2 run_vcd_devfull "$S" run horner3 --vcd /dev/full
    expect2 vectors_o_devfull "$S" vectors horner3 -o /dev/full
    expect2 run_json_stdout_full sh -c '"$0" run horner3 --json >/dev/full' "$S"
    expect2 run_table_stdout_full sh -c '"$0" run horner3 >/dev/full' "$S"
    expect2 run_all_stdout_full sh -c '"$0" run all >/dev/full' "$S"
    expect2 list_stdout_full sh -c '"$0" list >/dev/full' "$S"
    expect2 vectors_stdout_full sh -c '"$0" vectors horner3 >/dev/full' "$S"
    expect2 sweep_stdout_full sh -c '"$0" sweep horner3 --widths 8:9 -o "$1/sw" >/dev/full' "$S" "$T"
    expect2 help_stdout_full sh -c '"$0" run --help >/dev/full' "$S"
    [ -c /dev/full ] && ok devfull_still_device || fail devfull_still_device "$(ls -l /dev/full)"
else
    echo "skip ${PREFIX}devfull: /dev/full not available"
fi

# --- symbolic links: followed, the link kept, the target replaced --------
"$S" run horner3 --out "$T/direct.csv" >/dev/null
echo "old target" >"$T/target.csv"
ln -s target.csv "$T/link.csv"
"$S" run horner3 --out "$T/link.csv" >/dev/null; rc=$?
if [ $rc -eq 0 ] && [ -L "$T/link.csv" ] && cmp -s "$T/target.csv" "$T/direct.csv"; then ok out_through_symlink
else fail out_through_symlink "exit $rc, $(ls -l "$T/link.csv" "$T/target.csv")"; fi
ln -s vtarget.vec "$T/vlink.vec"            # dangling: the file appears at the target
"$S" vectors horner3 -o "$T/vlink.vec" && [ -L "$T/vlink.vec" ] && [ -f "$T/vtarget.vec" ] \
    && ok vectors_dangling_symlink || fail vectors_dangling_symlink "$(ls -l "$T"/v*)"

# --- FIFOs: written through (a reader gets the bytes, the FIFO stays) ----
if mkfifo "$T/fifo" 2>/dev/null; then
    "$S" vectors horner3 >"$T/vec_stdout"
    cat "$T/fifo" >"$T/fifo_got" &
    reader=$!
    "$S" vectors horner3 -o "$T/fifo"; rc=$?
    # A shadesim that replaced the FIFO (or never opened it) leaves the
    # reader waiting for a writer forever: end it rather than hang.
    if [ $rc -ne 0 ] || [ ! -p "$T/fifo" ]; then kill $reader 2>/dev/null; fi
    wait $reader
    if [ $rc -eq 0 ] && [ -p "$T/fifo" ] && cmp -s "$T/fifo_got" "$T/vec_stdout"; then ok vectors_fifo
    else fail vectors_fifo "exit $rc, $(ls -l "$T/fifo"), $(wc -c <"$T/fifo_got") bytes"; fi
else
    echo "skip ${PREFIX}vectors_fifo: mkfifo failed"
fi

# --- "-" is stdout for every output option --------------------------------
mkdir "$T/cwd"
(cd "$T/cwd" && "$S" run horner3 --vcd - >"$T/vcd_stdout" 2>"$T/vcd_err"); rc=$?
if [ $rc -eq 0 ] && head -1 "$T/vcd_stdout" | grep -q '^\$version' && grep -q '^\$enddefinitions' "$T/vcd_stdout" \
    && grep -q '^#' "$T/vcd_stdout" && ! grep -q '^unit horner3' "$T/vcd_stdout"; then ok vcd_dash_stdout
else fail vcd_dash_stdout "exit $rc: $(head -c 200 "$T/vcd_stdout")"; fi
grep -q '^unit horner3' "$T/vcd_err" && ok vcd_dash_report_on_stderr || fail vcd_dash_report_on_stderr "$(head -3 "$T/vcd_err")"
(cd "$T/cwd" && "$S" run horner3 --out - >"$T/csv_stdout" 2>/dev/null); rc=$?
if [ $rc -eq 0 ] && cmp -s "$T/csv_stdout" "$T/direct.csv"; then ok out_dash_stdout; else fail out_dash_stdout "exit $rc"; fi
(cd "$T/cwd" && "$S" vectors horner3 -o - >"$T/vec_dash") && cmp -s "$T/vec_dash" "$T/vec_stdout" \
    && ok vectors_dash_stdout || fail vectors_dash_stdout
[ -z "$(ls -A "$T/cwd")" ] && ok dash_makes_no_file || fail dash_makes_no_file "$(ls -A "$T/cwd")"
expect2 two_on_stdout "$S" run horner3 --vcd - --json
expect2 empty_out_path "$S" run horner3 --out ''
grep -q 'empty' "$T/err" && ok empty_path_message || fail empty_path_message "$(cat "$T/err")"

# --- file modes follow the umask -------------------------------------------
(umask 027 && "$S" run horner3 --out "$T/m.csv" --vcd "$T/m.vcd" >/dev/null && "$S" vectors horner3 -o "$T/m.vec")
for f in m.csv m.vcd m.vcd.gtkw m.vec; do
    p=$(ls -l "$T/$f" 2>/dev/null | cut -c1-10)
    [ "$p" = "-rw-r-----" ] && ok "umask_$f" || fail "umask_$f" "mode $p, expected -rw-r----- under umask 027"
done

# --- the .gtkw companion: any path length, exactly VCD.gtkw ---------------
long=$T
for i in 1 2 3 4 5; do long=$long/$(printf 'd%.0s' $(seq 1 200)); done
mkdir -p "$long"
"$S" run horner3 --vcd "$long/h.vcd" >/dev/null; rc=$?
if [ $rc -eq 0 ] && [ -f "$long/h.vcd.gtkw" ] && [ "$(ls -A "$long" | wc -l)" -eq 2 ]; then ok gtkw_long_path
else fail gtkw_long_path "exit $rc: $(ls -A "$long")"; fi
# A name whose .gtkw would pass the file-name limit: exit 2, nothing misnamed.
name=$(printf 'v%.0s' $(seq 1 252))
expect2 gtkw_name_too_long "$S" run horner3 --vcd "$T/cwd/$name"
if ls -A "$T/cwd" | grep -q '\.g'; then fail gtkw_no_misnamed_file "$(ls -A "$T/cwd")"; else ok gtkw_no_misnamed_file; fi
rm -f "$T/cwd/$name"

# --- merge checks what it reads as it reads it -----------------------------
head -c 3000000 /dev/zero | tr '\0' a >"$T/long.csv"
expect2 merge_long_line "$S" merge "$T/long.csv" -o "$T/m.csv"
grep -q 'long.csv:1: line longer than' "$T/err" && ok merge_long_line_message || fail merge_long_line_message "$(cat "$T/err")"
if command -v timeout >/dev/null 2>&1; then
    # /dev/zero never ends: only a reader that checks as it goes returns.
    expect2 merge_dev_zero timeout 60 "$S" merge /dev/zero -o "$T/m.csv"
else
    echo "skip ${PREFIX}merge_dev_zero: timeout not installed"
fi
"$S" sweep horner3 --widths 8:9 --shard 1/2 -o "$T/sh" >/dev/null && "$S" sweep horner3 --widths 8:9 --shard 2/2 -o "$T/sh" >/dev/null
"$S" merge "$T/sh/sweep-1-of-2.csv" "$T/sh/sweep-2-of-2.csv" -o - >"$T/merged_stdout" && \
    "$S" merge "$T/sh/sweep-1-of-2.csv" "$T/sh/sweep-2-of-2.csv" -o "$T/merged.csv" && cmp -s "$T/merged_stdout" "$T/merged.csv" \
    && ok merge_dash_stdout || fail merge_dash_stdout
[ -c /dev/full ] && expect2 merge_devfull "$S" merge "$T/sh/sweep-1-of-2.csv" "$T/sh/sweep-2-of-2.csv" -o /dev/full

# --- a run killed while it writes its VCD leaves no temporary -------------
# (SIGINT is tested in test_out.c: a background job of a non-interactive
# shell starts with SIGINT ignored, and an ignored signal stays ignored.)
mkdir "$T/kill"
"$S" vectors horner3 -n 100000 -o "$T/kill/big.vec"
for sig in TERM HUP; do
    "$S" run horner3 --vectors "$T/kill/big.vec" --vcd "$T/kill/big.vcd" >/dev/null 2>&1 &
    pid=$!
    # Wait (up to about 10 s) for the dump's temporary to appear.
    n=0
    while [ $n -lt 200 ] && ! ls -a "$T/kill" | grep -q '\.tmp-'; do sleep 0.05; n=$((n + 1)); done
    if ls -a "$T/kill" | grep -q '\.tmp-'; then
        kill -$sig $pid
        { wait $pid; rc=$?; } 2>/dev/null     # no "Terminated" from the shell
        # (exit 0: the run ended between the look and the kill, on a
        # fast machine; the temporary is then gone all the same)
        if [ $rc -gt 128 ]; then no_temp "killed_by_$sig" "$T/kill"
        elif [ $rc -eq 0 ]; then no_temp "ended_before_$sig" "$T/kill"
        else fail "killed_by_$sig" "exit $rc, not by the signal"; fi
    else
        wait $pid
        echo "skip ${PREFIX}killed_by_$sig: the run ended before its temporary was seen"
    fi
    rm -f "$T/kill/big.vcd" "$T/kill/big.vcd.gtkw"
done

# --- a sweep's files move into its folder as one set -----------------------
# consistent NAME DIR: summary.txt and sweep.csv of one sweep (same
# sweep_id), and target.json present exactly when the summary has a target.
consistent() {
    sid=$(sed -n 's/.*sweep_id \([0-9a-f]*\).*/\1/p' "$2/summary.txt" | head -1)
    cid=$(sed -n '2p' "$2/sweep.csv" | cut -d, -f3)
    if [ -z "$sid" ] || [ "$sid" != "$cid" ]; then fail "$1" "summary.txt sweep_id '$sid', sweep.csv '$cid'"; return; fi
    if grep -q '^target' "$2/summary.txt"; then t=1; else t=0; fi
    if [ -e "$2/target.json" ]; then j=1; else j=0; fi
    [ $t -eq $j ] && ok "$1" || fail "$1" "target in summary: $t, target.json: $j"
}
"$S" sweep horner3 --widths 8:9 -o "$T/set" >/dev/null
cp -r "$T/set" "$T/set_before"
"$S" sweep horner3 --widths 1:40 -n 20000 --target-error 0.01 -o "$T/set" >/dev/null 2>&1 &
pid=$!
sleep 0.3
kill -TERM $pid 2>/dev/null
{ wait $pid; } 2>/dev/null
diff -r "$T/set" "$T/set_before" >/dev/null && ok sweep_interrupted_leaves_folder || fail sweep_interrupted_leaves_folder "$(diff -rq "$T/set" "$T/set_before" | head -3)"
no_temp sweep_interrupted_no_temp "$T/set"
# Two sweeps into one folder at once, a few times: one whole set each time.
for round in 1 2 3; do
    "$S" sweep horner3 --widths 8:10 --target-error 1 -o "$T/set" >/dev/null 2>&1 &
    p1=$!
    "$S" sweep horner3 --widths 8:12 --round trunc,even -o "$T/set" >/dev/null 2>&1 &
    p2=$!
    wait $p1; wait $p2
    consistent "concurrent_sweeps_one_set_$round" "$T/set"
done
no_temp concurrent_sweeps_no_temp "$T/set"
