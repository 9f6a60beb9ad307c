#!/bin/sh
# cli_outset.sh - a verb's files are one set (docs/cli.md, "Output
# files"): a member that cannot be written (a link to /dev/full) fails the
# run with exit 2 and leaves the folder as it was; files of the user's
# (a FIFO, a link) named like an optional output are never removed; a
# symbolic link is written through (the linked file keeps its inode); a
# closed pipe on stdout is exit 2 with a message, not SIGPIPE (issue 26,
# "Outputs").
. tests/lib_cli.sh
PREFIX=cli_outset.

# snap DIR: a listing of DIR with each file's checksum (links as links).
snap() { (cd "$1" && for f in $(ls -A | sort); do
            if [ -L "$f" ]; then echo "$f -> $(readlink "$f")"
            elif [ -f "$f" ]; then echo "$f $(cksum <"$f")"
            elif [ -d "$f" ]; then echo "$f/"; snap "$f" | sed "s|^|$f/|"
            else echo "$f (special)"; fi
        done); }
# same NAME DIR BEFORE: DIR's listing equals the one saved in BEFORE.
same() { snap "$2" >"$T/now"; if cmp -s "$3" "$T/now"; then ok "$1"; else fail "$1" "$(diff "$3" "$T/now" | head -5 | tr '\n' ' ')"; fi; }
no_temps() { if ls -A "$2" | grep -q '\.tmp-'; then fail "$1" "temporaries left: $(ls -A "$2" | tr '\n' ' ')"; else ok "$1"; fi; }

# --- out of memory (ulimit -v): the contract's one line and exit status 3,
# and a sweep's old set left whole (it was replaced by rows "failed: out
# of memory", exit 1). The sanitizers reserve more address space than any
# such limit allows: the plain build only.
if [ -n "$ASAN" ]; then echo "skip ${PREFIX}oom: ulimit -v and the sanitizers' shadow memory exclude each other"
else
    # (-n's vectors are held in memory; a vector file is streamed in flat memory)
    expect oom_run 3 sh -c 'ulimit -v 150000 && exec "$0" run horner3 -n 600000' "$S"
    check oom_run_line grep -qx 'shadesim: out of memory' "$T/err"
    D=$T/oom
    "$S" sweep horner3 --widths 10:11 -n 1000 -o "$D" >/dev/null
    snap "$D" >"$T/before"
    # (a plain sweep streams its -n vectors in a few MB: a target search
    # holds them, 3M rows, and runs out)
    expect oom_sweep 3 sh -c 'ulimit -v 400000 && exec "$0" sweep horner3 --widths 10:11 -n 3000000 -j 2 --target-error 1e-3 -o "$1"' "$S" "$D"
    same oom_sweep_set_kept "$D" "$T/before"
fi

if [ ! -c /dev/full ]; then echo "skip ${PREFIX}dev_full: no /dev/full"; exit 0; fi

# --- sweep: summary.txt a link to /dev/full; the old set stays whole
D=$T/sw
"$S" sweep horner3 --widths 10:11 -o "$D" >/dev/null
rm "$D/summary.txt" && ln -s /dev/full "$D/summary.txt"
snap "$D" >"$T/before"
expect sweep_full_member 2 "$S" sweep horner3 --widths 10:13 -o "$D"
grep -q 'summary.txt: write failed: No space left on device' "$T/err" && ok sweep_full_member_message || fail sweep_full_member_message "$(cat "$T/err")"
same sweep_folder_unchanged "$D" "$T/before"
no_temps sweep_no_temporaries "$D"

# --- sweep: a FIFO and a link named like its optional outputs stay
rm "$D/summary.txt"
mkfifo "$D/target.json" && ln -s "$T/nowhere" "$D/target.csv"
expect sweep_user_files 0 "$S" sweep horner3 --widths 10:11 -o "$D"
if [ -p "$D/target.json" ] && [ -L "$D/target.csv" ]; then ok sweep_user_files_kept; else fail sweep_user_files_kept "$(ls -l "$D")"; fi
# a regular target.json of an earlier sweep does go
rm -f "$D/target.json" "$D/target.csv" && echo old >"$D/target.json"
"$S" sweep horner3 --widths 10:11 -o "$D" >/dev/null
[ ! -e "$D/target.json" ] && ok sweep_stale_regular_removed || fail sweep_stale_regular_removed

# --- scene: scene.json a link to /dev/full; no image appears
D=$T/sc
mkdir -p "$D" && ln -s /dev/full "$D/scene.json"
snap "$D" >"$T/before"
expect scene_full_member 2 "$S" scene sphere --set resolution=16x16 -o "$D"
same scene_folder_unchanged "$D" "$T/before"
no_temps scene_no_temporaries "$D"
# and over an earlier render: its images stay
rm "$D/scene.json"
"$S" scene sphere --set resolution=16x16 -o "$D" >/dev/null
rm "$D/scene.json" && ln -s /dev/full "$D/scene.json"
snap "$D" >"$T/before"
expect scene_full_member_again 2 "$S" scene sphere --set resolution=24x24 -o "$D"
same scene_old_render_kept "$D" "$T/before"

# --- verilog: the testbench a link to /dev/full; no module appears
D=$T/v
mkdir -p "$D" && ln -s /dev/full "$D/horner3_tb.v"
snap "$D" >"$T/before"
expect verilog_full_member 2 "$S" verilog horner3 -o "$D"
same verilog_folder_unchanged "$D" "$T/before"

# --- factor: report.csv a link to /dev/full; no map appears
D=$T/f
mkdir -p "$D" && ln -s /dev/full "$D/report.csv"
snap "$D" >"$T/before"
expect factor_full_member 2 "$S" factor blinn --res 8 --samples 2000 --heldout 500 -o "$D"
same factor_folder_unchanged "$D" "$T/before"

# The stability atlas and the report compute everything before their
# write fails (tens of seconds of CPU): make test alone (cli_stability and
# cli_report, both in tests/slow.list, run them whole).
if full_only; then
    # --- stability: one chart a link to /dev/full; no chart appears (the
    # chart's name as --help lists it: cli_stability checks that -o writes
    # the charts, and names them so)
    D=$T/st
    mkdir -p "$D"
    first=$("$S" stability --help | grep -o 'stability_[a-z_0-9]*\.svg' | head -1)
    if [ -z "$first" ]; then
        fail stability_charts "stability --help names no chart"
    else
        ln -s /dev/full "$D/$first"
        snap "$D" >"$T/before"
        expect stability_full_member 2 "$S" stability -o "$D"
        same stability_folder_unchanged "$D" "$T/before"
    fi

    # --- report: report.html a link to /dev/full; no CSV, scene or VCD
    D=$T/r
    mkdir -p "$D" && ln -s /dev/full "$D/report.html"
    snap "$D" >"$T/before"
    expect report_full_member 2 "$S" report -o "$D"
    same report_folder_unchanged "$D" "$T/before"
    no_temps report_no_temporaries "$D"
fi

# --- a symbolic link is written through: same file, same inode, and a
# hard link to it sees the bytes; the link is still a link
D=$T/lk
mkdir -p "$D" && echo old >"$D/real.csv" && ln "$D/real.csv" "$D/hard.csv" && ln -s real.csv "$D/link.csv"
ino=$(ls -i "$D/real.csv" | cut -d' ' -f1)
"$S" run horner3 --out "$D/link.csv" >/dev/null
if [ -L "$D/link.csv" ] && [ "$(ls -i "$D/real.csv" | cut -d' ' -f1)" = "$ino" ] && head -1 "$D/hard.csv" | grep -q '^index,'; then
    ok symlink_written_through
else
    fail symlink_written_through "$(ls -li "$D")"
fi
# the man page and docs/cli.md say so
"$S" --man | tr '\n' ' ' | grep -q 'symbolic link is written through, not replaced' && ok man_symlink || fail man_symlink
if [ -f docs/cli.md ]; then
    tr '\n' ' ' <docs/cli.md | grep -q 'a symbolic link), it is written   through, never replaced' && ok docs_symlink || fail docs_symlink
fi

# --- a closed pipe: exit 2 and one line, not death by SIGPIPE (141)
{ "$S" vectors horner3 -n 200000 2>"$T/perr"; echo $? >"$T/prc"; } | head -1 >/dev/null
rc=$(cat "$T/prc")
if [ "$rc" = 2 ] && grep -q '^shadesim: standard output: write failed: Broken pipe' "$T/perr"; then ok closed_pipe
else fail closed_pipe "exit $rc: $(cat "$T/perr")"; fi

# --- the other multi-file outputs: claims' charts, chart's charts, a
# scene --compare's three folders
# (claims computes every claim before its write fails: fifteen seconds of
# CPU under the sanitizers, where cli_claims runs the verb whole, text and
# JSON, and the other sets here the failing write; the plain build here)
if [ -n "$ASAN" ]; then echo "skip ${PREFIX}claims_full_member: the plain build runs it (cli_claims runs claims under the sanitizers)"
else
    D=$T/cl
    mkdir -p "$D" && ln -s /dev/full "$D/claims_cost.svg"
    snap "$D" >"$T/before"
    expect claims_full_member 2 "$S" claims -o "$D"
    same claims_folder_unchanged "$D" "$T/before"
fi
D=$T/ch
"$S" sweep horner3 --widths 10:11 -o "$T/chsrc" >/dev/null
mkdir -p "$D" && ln -s /dev/full "$D/area_vs_error.svg"
snap "$D" >"$T/before"
expect chart_full_member 2 "$S" chart "$T/chsrc/sweep.csv" -o "$D"
same chart_folder_unchanged "$D" "$T/before"
D=$T/cmp
mkdir -p "$D/auto" && ln -s /dev/full "$D/auto/scene.json"
snap "$D" >"$T/before"
expect compare_full_member 2 "$S" scene sphere --compare --set resolution=16x16 -o "$D"
same compare_folder_unchanged "$D" "$T/before"
