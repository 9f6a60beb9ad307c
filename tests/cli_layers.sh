#!/bin/sh
# cli_layers.sh - the include graph stays a stack with no circle. Every
# '#include "DIR/..."' of a layer's .c and .h files must name its own
# folder or one the table below lets it use:
#   sim/ (kernel, fixed point, primitives) and base/ (output files, JSON,
#   parallel-for, name lists) at the bottom, using nothing else;
#   chart/ and vectors/ on base/; units/ on sim/ and vectors/; scene/ on
#   vectors/ and sim/'s rounding names; testbench/ (the engine: run,
#   stream, batch, PPA, Verilog) on top of them, testbench/study/ (sweeps,
#   scenes through the hardware, stability, claims) on the engine, and
#   testbench/cli/ (main.c, one file per verb) on the studies.
# A layer is a folder; an include names the folder its header is in
# ("testbench/study/tb_sweep.h" is testbench/study's, not testbench's).
# Each line of the table only points down, so the graph has no circle.
# The checker is first run on a small tree with wrong includes planted, so
# this test shows on every run that it can fail.
. tests/lib_cli.sh
PREFIX=cli_layers.
plain_only

# uses LAYER: the folders LAYER may include from (itself first).
uses() {
    case $1 in
    sim)       echo "sim" ;;
    base)      echo "base" ;;
    chart)     echo "chart base" ;;
    vectors)   echo "vectors base" ;;
    units)     echo "units sim vectors base" ;;
    scene)     echo "scene sim vectors base" ;;
    testbench) echo "testbench sim base chart vectors units scene" ;;
    testbench/study) echo "testbench/study testbench sim base chart vectors units scene" ;;
    testbench/cli) echo "testbench/cli testbench/study testbench sim base chart vectors units scene" ;;
    *)         echo "" ;;
    esac
}
ALL="sim base chart vectors units scene testbench testbench/study testbench/cli"

# Includes allowed for now, "FILE INCLUDE" per line, each with its reason
# (none: the VCD writer takes a FILE* its caller opened, so sim/ includes
# only sim/).
KNOWN=""

# wrong ROOT: "FILE: includes INC" for each include that breaks the table
# (an include without a folder, like the generated "version.h", is the
# file's own folder's). One awk a layer over all its files (a process per
# file or include took most of this test's time).
wrong() {
    root=$1
    for layer in $ALL; do
        set --
        for f in "$root/$layer"/*.c "$root/$layer"/*.h; do [ -f "$f" ] && set -- "$@" "$f"; done
        [ $# -gt 0 ] || continue
        awk -v root="$root/" -v layer="$layer" -v allowed=" $(uses "$layer") " -v known="$KNOWN" '
            BEGIN { n = split(known, k, "\n"); for (i = 1; i <= n; i++) if (k[i] != "") kn[k[i]] = 1 }
            /^[[:space:]]*#[[:space:]]*include[[:space:]]*"[^"]*"/ {
                inc = $0
                sub(/^[[:space:]]*#[[:space:]]*include[[:space:]]*"/, "", inc)
                sub(/".*/, "", inc)
                top = inc
                if (top ~ /\//) sub(/\/[^\/]*$/, "", top); else top = layer
                if (index(allowed, " " top " ")) next
                rel = substr(FILENAME, length(root) + 1)
                if ((rel " " inc) in kn) next
                print rel ": includes " inc
            }' "$@"
    done
}

# 1. The checker fails where it should: a tree with one wrong include per
#    rule, and one clean file.
M=$T/mini
for d in $ALL; do mkdir -p "$M/$d"; done
printf '#include "sim/sim.h"\n#include <stdio.h>\n' >"$M/sim/ok.c"
printf '#include "units/unit.h"\n' >"$M/sim/up.c"                 # sim -> units
printf '#include "base/base_out.h"\n' >"$M/sim/side.h"             # sim -> base
printf '#include "sim/sim.h"\n' >"$M/base/down.c"                  # base -> sim
printf '#  include "testbench/tb.h"\n' >"$M/chart/up.c"             # chart -> testbench
printf '#include "testbench/cli/cli.h"\n' >"$M/units/up.c"         # units -> testbench/cli
printf '#include "units/unit.h"\n' >"$M/vectors/up.c"              # vectors -> units (a circle)
printf '#include "tests/tst.h"\n' >"$M/testbench/t.c"              # testbench -> tests
printf '#include "testbench/study/tb_sweep.h"\n' >"$M/testbench/up.h"  # engine -> study
printf '#include "testbench/cli/cli.h"\n' >"$M/testbench/up2.c"     # engine -> cli
printf '#include "testbench/tb.h"\n#include "testbench/cli/cli_opt.h"\n' >"$M/testbench/study/up.c"  # study -> cli
printf '#include "testbench/tb.h"\n#include "testbench/study/tb_sweep.h"\n#include "sim/sim.h"\n' \
    >"$M/testbench/cli/ok.c"                                        # cli -> study, engine, sim: fine
printf '#include "testbench/cli/cli.h"\n' >"$M/base/up.c"           # base -> testbench/cli
got=$(wrong "$M" | sort)
want=$(printf '%s\n' "base/down.c: includes sim/sim.h" "chart/up.c: includes testbench/tb.h" \
    "sim/side.h: includes base/base_out.h" "sim/up.c: includes units/unit.h" \
    "testbench/t.c: includes tests/tst.h" "units/up.c: includes testbench/cli/cli.h" \
    "vectors/up.c: includes units/unit.h" "testbench/up.h: includes testbench/study/tb_sweep.h" \
    "testbench/up2.c: includes testbench/cli/cli.h" "testbench/study/up.c: includes testbench/cli/cli_opt.h" \
    "base/up.c: includes testbench/cli/cli.h" | sort)
[ "$got" = "$want" ] && ok checker_finds_wrong_includes \
    || fail checker_finds_wrong_includes "$(printf 'found:\n%s\nexpected:\n%s' "$got" "$want" | tr '\n' '|')"

# 2. Every folder the Makefile builds as a layer is in the table.
layers=$(sed -n 's/^LAYERS[[:space:]]*:=[[:space:]]*//p' Makefile)
missing=""
for l in $layers; do [ -n "$(uses "$l")" ] || missing="$missing $l"; done
[ -n "$layers" ] && [ -z "$missing" ] && ok every_layer_has_rules \
    || fail every_layer_has_rules "Makefile LAYERS '$layers'; not in the table:$missing"

# 2b. Every folder of the tree that holds C sources (tests/ and bench/
#     aside: they may use any layer) is a layer, so a new sub-folder is
#     not left out of the check.
unlisted=""
for d in $(find . -path ./tests -prune -o -path ./bench -prune -o -path './build*' -prune -o -path ./bin -prune \
        -o -path ./.git -prune -o -name '*.[ch]' -print | sed 's|^\./||; s|/[^/]*$||' | sort -u); do
    case " $layers " in *" $d "*) ;; *) unlisted="$unlisted $d" ;; esac
done
[ -z "$unlisted" ] && ok every_source_folder_is_a_layer \
    || fail every_source_folder_is_a_layer "folders with C sources not in the Makefile's LAYERS:$unlisted"

# 2c. No verb calls a verb: a verb that needs another's figures gets them
#     from the engine or a study. verb_calls ROOT prints "FILE:LINE: calls
#     VERB" for each call of a verb's function (the "int cli_VERB(int argc,
#     char **argv);" lines of ROOT/testbench/cli/cli.h) in the command line's
#     files other than its own definition; main.c reaches the verbs through
#     their table, not by name.
verb_calls() {
    root=$1
    verbs=$(sed -n 's/^int \(cli_[a-z_0-9]*\)(int argc, char \*\*argv);.*/\1/p' "$root/testbench/cli/cli.h")
    set --
    for f in "$root"/testbench/cli/*.c; do [ -f "$f" ] && set -- "$@" "$f"; done
    [ $# -gt 0 ] || return 0
    # one awk over every file (a grep per file and verb took seconds)
    awk -v root="$root/" -v verbs="$verbs" '
        BEGIN { nv = split(verbs, v, /[ \n]+/) }
        {
            for (i = 1; i <= nv; i++)
                if (v[i] != "" && $0 ~ ("(^|[^A-Za-z0-9_])" v[i] "[(]") && $0 !~ ("^int " v[i] "[(]int argc"))
                    print substr(FILENAME, length(root) + 1) ":" FNR ": calls " v[i]
        }' "$@"
}
V=$T/verbs
mkdir -p "$V/testbench/cli"
printf 'int cli_aa(int argc, char **argv);\nint cli_bb(int argc, char **argv);\n' >"$V/testbench/cli/cli.h"
printf 'int cli_aa(int argc, char **argv)\n{\n    return cli_bb(argc, argv);\n}\n' >"$V/testbench/cli/aa.c"
printf 'int cli_bb(int argc, char **argv) { return xcli_aa(argc, argv); }\n' >"$V/testbench/cli/bb.c"
got=$(verb_calls "$V")
[ "$got" = "testbench/cli/aa.c:3: calls cli_bb" ] && ok checker_finds_verb_calls \
    || fail checker_finds_verb_calls "found '$(echo "$got" | tr '\n' '|')', expected 'testbench/cli/aa.c:3: calls cli_bb'"
calls=$(verb_calls .)
nverbs=$(grep -c '^int cli_[a-z_0-9]*(int argc, char \*\*argv);' testbench/cli/cli.h)
[ -z "$calls" ] && [ "$nverbs" -gt 5 ] && ok no_verb_calls_a_verb \
    || fail no_verb_calls_a_verb "$nverbs verbs in testbench/cli/cli.h; $(echo "$calls" | head -5 | tr '\n' ';')"

# 3. The tree itself.
bad=$(wrong .)
[ -z "$bad" ] && ok includes_point_down || fail includes_point_down "$(echo "$bad" | head -5 | tr '\n' ';')"

# 4. An allowed exception that is no longer needed is removed from KNOWN.
stale=""
while read -r file inc; do
    [ -n "$file" ] || continue
    grep -q "^[[:space:]]*#[[:space:]]*include[[:space:]]*\"$inc\"" "$file" 2>/dev/null || stale="$stale $file:$inc"
done <<EOK
$KNOWN
EOK
[ -z "$stale" ] && ok known_exceptions_current \
    || fail known_exceptions_current "no longer included, remove from KNOWN in tests/cli_layers.sh:$stale"

# 5. No two files of the library call each other (a circle the includes
#    do not show: two .c files sharing one header): helpers both need go
#    to a leaf file that calls neither. circles ARCHIVE prints "A.o <->
#    B.o" for each pair of its members where each uses a symbol the other
#    defines. Allowed, "A.o B.o" (B a pattern) with the reason:
#    the registry (units/unit.c lists every unit's descriptor, and every
#    unit calls its helpers); the span unit's descriptor and its halves
#    (the hardware and the bound, each calling back the descriptor's
#    table); the scene's description and file reader (scene files are
#    being reworked on their own); the delay model's live bits (sim_live
#    walks the element records sim_prim_describe gives, and an adder's
#    cost in sim_prim asks it which bits vary: to be split when the
#    record lookup moves to a leaf); the netlist reader and tb_build (a
#    file's fn=unit logic takes its function from the built-in unit,
#    built by tb_build, which builds a file's unit through the reader).
KNOWN_CALLS="unit.o unit_*.o
unit_span.o unit_span_bound.o
unit_span.o unit_span_hw.o
scene_desc.o scene_file.o
sim_live.o sim_prim.o
tb_build.o tb_netlist_read.o"
circles() {
    { nm -A -g --defined-only "$1" | awk '{ n = split($1, a, ":"); print "D", a[n - 1], $NF }'
      nm -A -u "$1" | awk '{ n = split($1, a, ":"); print "U", a[n - 1], $NF }'; } 2>/dev/null |
    awk '$1 == "D" { def[$3] = $2; next } { use[NR] = $2 " " $3 }
         END { for (i in use) { split(use[i], x, " "); if ((x[2] in def) && def[x[2]] != x[1]) e[x[1] " " def[x[2]]] = 1 }
               for (k in e) { split(k, y, " "); if (((y[2] " " y[1]) in e) && y[1] < y[2]) print y[1] " <-> " y[2] } }' |
    sort | while read -r a arrow b; do
        known=0
        while read -r ka kb; do
            case "$a $b" in "$ka "$kb) known=1 ;; esac   # (kb unquoted: a pattern)
            case "$b $a" in "$ka "$kb) known=1 ;; esac
        done <<EOK
$KNOWN_CALLS
EOK
        [ $known = 1 ] || echo "$a $arrow $b"
    done
}
b=${TST_BUILD:-build}
if ! command -v nm >/dev/null 2>&1 || ! command -v ar >/dev/null 2>&1; then
    echo "skip ${PREFIX}no_file_circles: nm or ar not installed"
elif [ ! -f "$b/libshadesim.a" ]; then
    fail no_file_circles "no $b/libshadesim.a"
else
    C=$T/calls
    mkdir -p "$C"
    printf 'int fb(int);\nint fa(int x) { return x ? fb(x - 1) : 0; }\n' >"$C/pa.c"    # pa <-> pb
    printf 'int fa(int);\nint fb(int x) { return fa(x); }\n' >"$C/pb.c"
    printf 'int fa(int);\nint fc(int x) { return fa(x); }\n' >"$C/pc.c"               # pc -> pa only
    printf 'int fe(int);\nint unit_x(int x) { return fe(x); }\n' >"$C/unit_x.c"       # the registry's
    printf 'int unit_x(int);\nint fe(int x) { return x; }\nint fu(int x) { return unit_x(x); }\n' >"$C/unit.c"
    for f in pa pb pc unit_x unit; do ${CC:-cc} -c -o "$C/$f.o" "$C/$f.c" 2>/dev/null; done
    (cd "$C" && ar rcs lib.a pa.o pb.o pc.o unit_x.o unit.o)
    got=$(circles "$C/lib.a")
    [ "$got" = "pa.o <-> pb.o" ] && ok checker_finds_file_circles \
        || fail checker_finds_file_circles "found '$(echo "$got" | tr '\n' '|')', expected 'pa.o <-> pb.o'"
    got=$(circles "$b/libshadesim.a")
    [ -z "$got" ] && ok no_file_circles || fail no_file_circles "$(echo "$got" | head -5 | tr '\n' ';')"
fi
