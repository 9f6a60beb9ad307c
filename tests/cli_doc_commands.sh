#!/bin/sh
# cli_doc_commands.sh - every shadesim command README.md and docs/*.md show
# in a code block runs, and prints what the doc says it prints.
#
# A command is a code-block line (indented by four spaces after a blank
# line, or inside a ``` fence) that is "$ shadesim ...", "$ bin/shadesim
# ..." or the same without "$ "; "mkdir -p DIR" lines run too (the docs
# make out/ before the first single-file output into it). Both names mean
# the shadesim under test. Each doc's commands run in order in a scratch
# folder of their own (a later command may read what an earlier one
# wrote), with SHADESIM_HOME at the checkout, so nothing is written into it.
#
# A command fails on exit status 2 (bad usage: the doc shows an option or
# form that does not exist) unless the table below expects it, on a crash
# (a signal) and on anything but 0 or 1. The lines a doc shows after a
# "$" command, up to the next command or the block's end, are its output:
# each must be a line of the command's stdout+stderr exactly (trailing
# blanks aside). A line "..." stands for lines left out, and "..." inside
# a line for part of one. The failure names the doc line that differs and
# the output line that comes closest, so whoever changes an output can fix
# the doc at once.
#
# Commands too slow for the suite run with smaller arguments (the table's
# "=>" lines; the whole test takes about 10 s of CPU); their documented
# output came from the full arguments, so it is compared only when a
# command runs as written. A few commands cannot
# run here (placeholders, the reader's own files, tools not installed):
# each is listed with its reason, and printed as a "skip" line.
. tests/lib_cli.sh
PREFIX=cli_doc_commands.

case "${TST_BUILD:-}" in
*-asan) echo "skip ${PREFIX}all: runs in the plain build only"; exit 0 ;;
esac
case $S in /*) ;; *) S=$(pwd)/$S ;; esac
export SHADESIM_HOME
SHADESIM_HOME=$(cd "$SHADESIM_HOME" && pwd)

# The table: a doc's command (without "$ ", its shadesim and its "# ..."
# comment, blanks squeezed), then
#   => ARGS       run these arguments instead (too slow as written, or a
#                 placeholder filled in); the shown output is not compared
#   == skip: WHY  do not run it, say why
#   == status N   the doc shows it failing with exit status N
rules=$(cat <<'EOF'
VERB [options]                                        == skip: synopsis (VERB is a placeholder)
help VERB                                             => help run
--help | --version | --man                            == skip: synopsis of three alternatives
scene my.scene --set resolution=256x256 -j 2          == skip: my.scene is the reader's own scene file
stability -o DIR                                      => stability -o out/stability
scene face --set unit=out/s3.dp -o out/scene-s3       => scene face --set unit=out/s3.dp --set resolution=64x64 -o out/scene-s3
merge DIR/sweep-*-of-N.csv -o DIR/sweep.csv           == skip: DIR and N are placeholders (README's merge runs)
cosim horner3 --rtl my/horner3.v [--rtl my/more.v ...] [--top NAME] == skip: synopsis (my/horner3.v is the reader's own design)
run horner3 --vectors indep.vec --fmt a=s7.13 --fmt b=s7.13 --fmt c=s7.14 --fmt d=s7.14 --fmt t=u1.19 --fmt y=s11.14 --fmt mx1=s11.13 --fmt mul=s12.14 --fmt mx2=s11.14 --fmt bk=s11.14 --fmt sm=s11.14 --fmt rg=s11.14 == skip: indep.vec is made by the awk line before it (tests/cli_ranges.sh runs the same check)
run horner3 --fmt mul=s7.12:foo                       == status 2
run horner3 --width 4                                 == status 2
scene face --sweep                                    => scene face --sweep "L=4,8;terms=3,5" --set resolution=128x128
scene face --sweep -j 2 -o out/sweep                  => scene face --sweep "L=4,8;terms=3,5" --set resolution=128x128 -j 2 -o out/sweep
scene face --set policy=adaptive-region --set terms=5 --target-nmse 1e-4                  => scene face --set policy=adaptive-region --set terms=5 --target-nmse 1e-3 --set resolution=64x64 -j 2
scene face --set policy=adaptive-region --set terms=5 --target-nmse 1e-4 -j 2 -o out/search => scene face --set policy=adaptive-region --set terms=5 --target-nmse 1e-3 --set resolution=64x64 -j 2 -o out/search
EOF
)

# The commands and their shown output, from every doc, as lines
#   C FILE LINE ISDOLLAR COMMAND     and     O FILE LINE TEXT
awk '
FNR == 1 { fence = 0; blank = 1; ind = 0; cmd = 0; cont = ""; contline = 0 }
{
    if ($0 ~ /^ *```/) { fence = !fence; cmd = 0; blank = 0; next }
    if (fence) text = $0
    else if ($0 ~ /^    / && (blank || ind)) { ind = 1; text = substr($0, 5) }
    else if ($0 ~ /^[ \t]*$/) { blank = 1; if (!ind) cmd = 0; next }
    else { ind = 0; cmd = 0; blank = 0; next }
    blank = 0
    # a command continued on the next line (a trailing backslash): joined
    if (cont != "") { text = cont " " text; sub(/^[ \t]+/, "", text); gsub(/  +/, " ", text) }
    if (text ~ /\\$/ && (cont != "" || text ~ /^(\$ )?(bin\/)?shadesim /)) {
        cont = substr(text, 1, length(text) - 1); sub(/[ \t]+$/, "", cont); contline = contline ? contline : FNR; next
    }
    cline = contline ? contline : FNR
    cont = ""; contline = 0
    dollar = 0
    if (text ~ /^\$ /) { dollar = 1; text = substr(text, 3) }
    if (text ~ /^(bin\/)?shadesim( |$)/ || text ~ /^mkdir -p [^ ]+$/) {
        print "C " FILENAME " " cline " " dollar " " text
        cmd = dollar
        next
    }
    if (dollar) { cmd = 0; next }
    if (cmd && text !~ /^[ \t]*$/) print "O " FILENAME " " FNR " " text
}' README.md docs/*.md >"$T/doc"

n_cmd=$(grep -c '^C ' "$T/doc")
check found_commands [ "$n_cmd" -ge 40 ]

# timeout(1) where there is one: a hung command fails instead of hanging
to=
command -v timeout >/dev/null 2>&1 && to="timeout 300"

# compare DOCFILE CMDLINE WHAT OUTFILE: each shown line of the command at
# DOCFILE:CMDLINE is a line of OUTFILE; prints a FAIL line per one that is not.
compare() {
    awk -v f="$1" -v l="$2" -v what="$3" -v pre="$PREFIX" -v outf="$4" '
    function trim(s) { sub(/[ \t]+$/, "", s); return s }
    # s matches p, where "..." in p stands for any text
    function matches(s, p,   n, parts, i, at, k) {
        if (index(p, "...") == 0) return s == p
        n = split(p, parts, /\.\.\./)
        at = 1
        for (i = 1; i <= n; i++) {
            if (parts[i] == "") continue
            k = index(substr(s, at), parts[i])
            if (k == 0 || (i == 1 && k != 1)) return 0
            at += k - 1 + length(parts[i])
        }
        return parts[n] == "" || substr(s, length(s) - length(parts[n]) + 1) == parts[n]
    }
    # the output line sharing the longest start with p
    function closest(p,   i, j, best, bl) {
        best = ""; bl = -1
        for (i = 1; i <= no; i++) {
            for (j = 1; j <= length(p) && substr(p, j, 1) == substr(out[i], j, 1); j++) ;
            if (j > bl) { bl = j; best = out[i] }
        }
        return best
    }
    BEGIN {
        while ((getline s < outf) > 0) out[++no] = trim(s)
        bad = 0
    }
    $1 == "C" && $2 == f && $3 == l { mine = 1; next }
    $1 == "C" { mine = 0; next }
    $1 == "O" && mine {
        text = $0
        sub(/^O [^ ]+ [0-9]+ /, "", text)
        text = trim(text)
        if (text ~ /^[ \t]*\.\.\.$/) next
        found = 0
        for (i = 1; i <= no && !found; i++) if (matches(out[i], text)) found = 1
        if (!found) {
            printf "FAIL %s%s:%s: the output of \"%s\" (%s:%s) has no line\n    %s\n  closest output line:\n    %s\n", \
                pre, f, $3, what, f, l, text, closest(text)
            bad = 1
        }
    }
    END { exit bad }' "$T/doc"
}

ran=0 mapped=0 skipped=0 prev=
LIBERTY=$(cd "$SHADESIM_HOME/.." && pwd)/shared/liberty/nangate45_typ.lib.gz
while read -r kind file line dollar cmd; do
    [ "$kind" = C ] || continue
    name="$file:$line"
    if [ "$file" != "$prev" ]; then
        # a fresh scratch folder per doc
        W=$T/run/$(echo "$file" | tr '/.' '__')
        mkdir -p "$W"
        # the docs' commands run from a checkout: its tests/ and vectors/
        # files (tests/rtl/horner3_hand.v, vectors/horner3.vec) are there
        ln -s "$SHADESIM_HOME/tests" "$W/tests"
        ln -s "$SHADESIM_HOME/vectors" "$W/vectors"
        ln -s "$SHADESIM_HOME/examples" "$W/examples"
        # synth --sta's library, as a reader who downloaded it has it:
        # the NanGate45 Liberty kept beside the checkout (never in it)
        [ -r "$LIBERTY" ] && ln -s "$LIBERTY" "$W/nangate45_typ.lib.gz"
        prev=$file
    fi
    case $cmd in
    mkdir\ -p\ *)
        (cd "$W" && eval "$cmd") || fail "$name" "$cmd failed"
        continue ;;
    esac
    # the arguments: shadesim's name and a trailing comment off, blanks squeezed
    args=$(printf '%s\n' "$cmd" | sed -e 's/^\(bin\/\)\{0,1\}shadesim//' -e 's/[ 	]#.*$//' \
        | tr -s ' ' | sed -e 's/^ //' -e 's/ $//')
    rule=$(printf '%s\n' "$rules" | awk -v a="$args" '{
        i = index($0, " => "); j = index($0, " == ")
        if (i) { k = substr($0, 1, i - 1); v = "=> " substr($0, i + 4) }
        else if (j) { k = substr($0, 1, j - 1); v = "== " substr($0, j + 4) }
        else next
        sub(/ +$/, "", k)
        if (k == a) { print v; exit }
    }')
    [ -n "$rule" ] && printf '%s\n' "$args" >>"$T/used"
    want=
    run=$args
    case $rule in
    "== skip:"*) echo "skip ${PREFIX}$name: shadesim $args: ${rule#== skip: }"; skipped=$((skipped + 1)); continue ;;
    "== status "*) want=${rule#== status } ;;
    "=> "*) run=${rule#=> }; mapped=$((mapped + 1)) ;;
    esac
    # tools: cosim needs Icarus Verilog (or Verilator), synth Yosys (and
    # OpenSTA or nextpnr for --sta and --fpga)
    tool=
    case $args in
    *--fst*) tool=vcd2fst ;;
    cosim*--sim\ verilator*) tool=verilator ;;
    cosim*) tool=iverilog ;;
    synth*--sta*) tool=sta ;;
    synth*--fpga*) tool=nextpnr-ice40 ;;
    synth*) tool=yosys ;;
    esac
    case $args in *nangate45_typ.lib.gz*)
        if [ ! -r "$LIBERTY" ]; then echo "skip ${PREFIX}$name: no NanGate45 Liberty beside the checkout"; skipped=$((skipped + 1)); continue; fi ;;
    esac
    if [ -n "$tool" ] && ! command -v "$tool" >/dev/null 2>&1; then
        echo "skip ${PREFIX}$name: $tool not installed"; skipped=$((skipped + 1)); continue
    fi
    # Run it, split by the shell as the doc's reader's would be. A command
    # that only prints (synth, claims: no -o, nothing read from the scratch
    # folder) and that an earlier doc ran already is not run again: its
    # output and status are the earlier run's (two docs show `synth
    # horner3`, 20 s of Yosys each).
    memo=
    case " $run " in
    " synth "*" -o "*|" claims "*" -o "*) ;;
    " synth "*|" claims "*) memo=$T/memo/$(printf '%s' "$run" | cksum | tr ' ' _) ;;
    esac
    if [ -n "$memo" ] && [ -f "$memo.st" ]; then
        cp "$memo.out" "$T/out"; st=$(cat "$memo.st")
    else
        (cd "$W" && eval "$to \"\$S\" $run") >"$T/out" 2>&1 </dev/null
        st=$?
        if [ -n "$memo" ]; then mkdir -p "$T/memo" && cp "$T/out" "$memo.out" && echo "$st" >"$memo.st"; fi
    fi
    ran=$((ran + 1))
    if [ -n "$want" ]; then
        [ "$st" -eq "$want" ] || { fail "$name" "shadesim $args: exit status $st, the doc shows $want: $(head -c 300 "$T/out")"; continue; }
    elif [ "$st" -eq 2 ]; then
        fail "$name" "shadesim $run: exit status 2 (bad usage: the doc shows an option or form that does not exist?): $(head -c 300 "$T/out")"; continue
    elif [ "$st" -ne 0 ] && [ "$st" -ne 1 ]; then
        fail "$name" "shadesim $run: exit status $st (a crash, a signal or a timeout): $(head -c 300 "$T/out")"; continue
    fi
    # "--vcd FILE ... # 1,528,173 bytes": the dump has that size
    size=$(printf '%s\n' "$cmd" | sed -n 's/.*--vcd \([^ ]*\.vcd\) .*#  *\([0-9,]*\) bytes$/\1 \2/p')
    if [ -n "$size" ] && [ "$run" = "$args" ]; then
        got=$(wc -c <"$W/${size%% *}" 2>/dev/null | tr -d ' ')
        want=$(echo "${size#* }" | tr -d ,)
        [ "$got" = "$want" ] || { fail "$name" "${size%% *} has ${got:-no} bytes, the doc says $want"; continue; }
    fi
    if [ "$dollar" = 1 ] && [ "$run" = "$args" ]; then
        compare "$file" "$line" "shadesim $args" "$T/out" && ok "$name"
    else
        ok "$name"
    fi
done <"$T/doc"
echo "  $n_cmd doc commands: $ran run ($mapped with smaller arguments), $skipped skipped"

# A rule whose command no doc shows any more is stale: a doc's command was
# edited and now runs as written (perhaps slowly), or was removed.
stale=$(printf '%s\n' "$rules" | sed -e 's/ *=> .*$//' -e 's/ *== .*$//' | while read -r k; do
    grep -qxF -- "$k" "$T/used" 2>/dev/null || printf ' [%s]' "$k"; done)
check rules_all_used [ -z "$stale" ]
if [ -n "$stale" ]; then echo "  rules matching no doc command (update the table):$stale"; fi
