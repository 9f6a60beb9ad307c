#!/bin/sh
# cli_docs.sh - the product text stands on its own: README.md, docs/, every
# verb's --help, the man page and the outputs of list and claims never send
# the reader to files they do not have (../shared, SPEC), never name a paper
# by an internal number ("seed 000") or talk of "the brief"; every paper
# they cite by short name is defined in docs/references.md; README's first
# commands are make run and make test; the LICENSE is there. The source
# (comments and strings) avoids the same words.
. tests/lib_cli.sh
PREFIX=cli_docs.

# The forbidden words, as one extended regular expression.
# Also a paper named by its number ("000 sec. III", "004 Table 1") and the
# papers called "the seeds".
q="'"
bad="\.\./shared|shared/seeds|shared/SPEC|\bSPEC\b|[Ss]eeds? 00[0-9]|[Ss]eed 0[0-9]{2}|the brief|seeds? \(0"
bad="$bad|\b00[0-4],? (sec|eqs?|Figs?|IV|III|Table)\b|[Tt]he seeds\b|[Tt]he seed${q}s|seeds${q}"

notin() { ! grep -qE "$bad" "$1"; }

hits=$(grep -rInE "$bad" README.md docs/ 2>/dev/null | head -5)
check readme_docs_self_contained [ -z "$hits" ]
[ -n "$hits" ] && echo "$hits" | sed 's/^/  /'

# The source speaks the same language: comments and strings of every
# layer, the benchmarks, the tests and the Makefile (this file excepted:
# it names the words it forbids). The planted file shows the scan bites.
src_hits() { grep -rInE "$bad" "$@" --include='*.c' --include='*.h' --include='*.sh' --include='*.v' \
    --include='*.cpp' --include=Makefile 2>/dev/null | grep -v '^tests/cli_docs.sh:'; }
mkdir -p "$T/plant" && printf '/* the seed'"'"'s BK (SPEC 2.1) */\n' >"$T/plant/p.c"
check source_scan_finds_planted [ -n "$(src_hits "$T/plant")" ]
hits=$(src_hits sim base chart vectors units scene testbench bench tests Makefile | head -5)
check source_self_contained [ -z "$hits" ]
[ -n "$hits" ] && echo "$hits" | sed 's/^/  /'

# Every verb that --help lists, and the top level.
"$S" --help >"$T/top" 2>&1
verbs=$(sed -n '/^verbs:/,/^$/s/^  \([a-z0-9_]*\) .*/\1/p' "$T/top")
check verbs_listed [ "$(echo $verbs | wc -w)" -ge 7 ]
badverbs=
for v in $verbs; do
    "$S" "$v" --help >"$T/help_$v" 2>&1 || badverbs="$badverbs $v(status)"
    grep -qE "$bad" "$T/help_$v" && badverbs="$badverbs $v"
done
grep -qE "$bad" "$T/top" && badverbs="$badverbs (shadesim --help)"
check help_self_contained [ -z "$badverbs" ]
[ -n "$badverbs" ] && echo "  offending --help:$badverbs"

"$S" --man >"$T/man" 2>&1
check man_self_contained notin "$T/man"

"$S" list >"$T/list" 2>&1
check list_self_contained notin "$T/list"
check list_cites_papers grep -q '^  from Nechyporuk & Romanyuk (2020)' "$T/list"

# claims takes a few seconds; the plain build is enough to read its text,
# and make test (make test-quick leaves it out, as it does cli_claims).
case "${TST_BUILD:-}" in
*-asan) echo "skip ${PREFIX}claims_self_contained: runs in the plain build only" ;;
*)
    if full_only; then
        "$S" claims >"$T/claims" 2>&1
        check claims_self_contained notin "$T/claims"
        cat "$T/claims" >>"$T/list"
    fi ;;
esac

# Every short citation "Name (2020)", "Name & Name (2020)", "Name et al.
# (2022)" or "... et al. (SPIE)" used in list/claims output or the docs
# is defined as a bold entry of docs/references.md.
cites=$(cat "$T/list" docs/*.md README.md | grep -oE "[A-Z][a-z]+( & [A-Z][a-z]+| et al\.) \(((19|20)[0-9]{2}|SPIE)\)" | sort -u)
undefined=
for c in $(echo "$cites" | tr ' ' '~'); do
    c=$(echo "$c" | tr '~' ' ')
    grep -qF "**$c" docs/references.md || grep -qF "**S. O. $c" docs/references.md || undefined="$undefined [$c]"
done
check citations_defined [ -n "$cites" -a -z "$undefined" ]
[ -n "$undefined" ] && echo "  not in docs/references.md:$undefined"

# README: the two commands come first, exactly.
first2=$(grep -E '^    make ' README.md | head -2 | awk '{print $1, $2}' | tr '\n' ';')
check readme_two_commands_first [ "$first2" = "make run;make test;" ]
check license_mit grep -q 'MIT License' LICENSE
check license_copyright grep -q 'Copyright (c) 2026 the shadesim developers' LICENSE
# Every docs page the README's index names exists, and every docs page is named.
unnamed=
for f in docs/*.md; do grep -qF "$f" README.md || unnamed="$unnamed $f"; done
check readme_indexes_every_doc [ -z "$unnamed" ]
[ -n "$unnamed" ] && echo "  not in README.md:$unnamed"
dangling=
for f in $(grep -oE 'docs/[a-z_]+\.md' README.md | sort -u); do [ -f "$f" ] || dangling="$dangling $f"; done
check readme_links_exist [ -z "$dangling" ]
