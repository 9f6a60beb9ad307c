#!/bin/sh
# cli_gold.sh - the fast kernel (run --kernel: inline operations, logic
# tables, clock edges in place) gives, for every unit and schedule on its
# default vectors and a few runs that overflow, the counters the kernel's
# reference gave (run --reference, the plain evaluate/update loop):
# tests/gold/counters.txt, which `make gold` makes. One line per run; a
# difference prints the gold line and the kernel's.
. tests/lib_cli.sh
no_leak_check   # (lib_cli.sh: the same verbs over and over)
PREFIX=cli_gold.
G=tests/gold/counters.txt
[ -s "$G" ] || { fail file "$G missing (make gold)"; exit 0; }
if ! sh tests/gold/make_gold.sh "$S" --kernel >"$T/now" 2>"$T/err"; then
    fail kernel "$(head -c 300 "$T/err")"; exit 0
fi
grep -v '^#' "$G" >"$T/gold"
grep -v '^#' "$T/now" >"$T/kern"
# every run of the gold file, against the kernel's line of the same name
while read -r name rest; do
    got=$(grep "^$name " "$T/kern" | head -1)
    if [ -z "$got" ]; then fail "$name" "the kernel has no such run"
    elif [ "$got" != "$name $rest" ]; then fail "$name" "gold: $name $rest; kernel: $got"
    else ok "$name"; fi
done <"$T/gold"
# and no run the gold file lacks (a new unit or schedule: make gold)
new=$(cut -d' ' -f1 "$T/kern" | while read -r name; do grep -q "^$name " "$T/gold" || echo "$name"; done)
if [ -n "$new" ]; then fail complete "not in $G (make gold): $(echo $new)"; else ok complete; fi
