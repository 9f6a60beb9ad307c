#!/bin/sh
# cli_gold.sh - the fast kernel (run --kernel: inline operations, logic
# tables, clock edges in place) gives, for every unit and schedule on its
# default vectors and a few runs that overflow, the counters the kernel's
# reference gave (run --reference, the plain evaluate/update loop):
# tests/gold/counters.txt, which `make gold` makes. One line per run; a
# difference prints the gold line and the kernel's. The reference itself
# is held to the file's overflowing runs.
. tests/lib_cli.sh
no_leak_check   # (lib_cli.sh: the same verbs over and over)
PREFIX=cli_gold.
# Under the sanitizers: the counters are the plain build's and the
# portable one's; what the sanitizers would add, the kernel and its
# reference on every unit and schedule, test_reference runs there in
# process (here: ten seconds of CPU, a process a run).
if [ -n "$ASAN" ]; then echo "skip cli_gold: the plain and portable builds compare the counters (test_reference runs every unit and schedule under the sanitizers)"; exit 0; fi
G=tests/gold/counters.txt
[ -s "$G" ] || { fail file "$G missing (make gold)"; exit 0; }
if ! sh tests/gold/make_gold.sh "$S" --kernel >"$T/now" 2>"$T/err"; then
    fail kernel "$(head -c 300 "$T/err")"; exit 0
fi
grep -v '^#' "$G" >"$T/gold"
grep -v '^#' "$T/now" >"$T/kern"
# every run of the gold file, against the kernel's line of the same name,
# and no run the gold file lacks (a new unit or schedule: make gold); one
# awk over both files
awk -v G="$G" -v P="$PREFIX" '
    FNR == NR { k[$1] = $0; order[++nk] = $1; next }
    { g[$1] = 1
      if (!($1 in k)) print "FAIL " P $1 ": the kernel has no such run"
      else if (k[$1] != $0) print "FAIL " P $1 ": gold: " $0 "; kernel: " k[$1]
      else print "ok " P $1 }
    END { new = ""
          for (i = 1; i <= nk; i++) if (!(order[i] in g)) new = new " " order[i]
          if (new != "") print "FAIL " P "complete: not in " G " (make gold):" new
          else print "ok " P "complete" }' "$T/kern" "$T/gold"

# the reference on the gold file's overflowing runs, line for line (on the
# others tests/cli_engine.sh holds it to the kernel's JSON, counters and
# all; make gold writes the whole file from it)
if ! sh tests/gold/make_gold.sh "$S" --reference overflows >"$T/ref" 2>"$T/err"; then
    fail reference "$(head -c 300 "$T/err")"; exit 0
fi
grep -v '^#' "$T/ref" | while read -r name rest; do
    want=$(grep "^$name " "$T/gold")
    if [ "$want" = "$name $rest" ]; then ok "reference.$name"; else fail "reference.$name" "gold: $want; reference: $name $rest"; fi
done
