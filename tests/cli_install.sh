#!/bin/sh
# cli_install.sh - make install into a temporary prefix, then the installed
# binary used as a stranger would: from /, without SHADESIM_HOME, finding
# its default vectors beside itself; SHADESIM_HOME overriding that; the man
# page; --version; make uninstall. The Makefile's own install recipe is
# run, with the binary under test (INSTALL_BIN), so nothing is compiled.
. tests/lib_cli.sh
PREFIX=cli_install.
root=$(pwd)
P="$T/prefix dir"         # a space in the path on purpose

# ---- install ----
if command -v make >/dev/null 2>&1; then
    env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make -s --no-print-directory install PREFIX="$P" INSTALL_BIN="$S" >"$T/inst.out" 2>&1
    rc=$?
else
    echo "skip ${PREFIX}install: make not installed"; exit 0
fi
check install_exit_0 [ $rc -eq 0 ]
[ $rc -ne 0 ] && sed -n "1,5s/^/  /p" "$T/inst.out"
check install_binary [ -x "$P/bin/shadesim" ]
nsrc=$(ls vectors/*.vec | wc -l)
ninst=$(ls "$P/share/shadesim/vectors/"*.vec 2>/dev/null | wc -l)
check install_every_vector_file [ "$nsrc" -gt 10 -a "$ninst" -eq "$nsrc" ]
same=1
for f in vectors/*.vec; do cmp -s "$f" "$P/share/shadesim/vectors/$(basename "$f")" || same=0; done
check install_vectors_identical [ $same -eq 1 ]
check install_man_page [ -s "$P/share/man/man1/shadesim.1" ]
check install_docs [ -s "$P/share/doc/shadesim/README.md" -a -s "$P/share/doc/shadesim/LICENSE" -a -s "$P/share/doc/shadesim/references.md" ]
check install_no_temporaries [ -z "$(find "$P" -name '*.tmp')" ]

# ---- the installed binary from /, finding its data from its own place ----
(cd / && env -u SHADESIM_HOME "$P/bin/shadesim" run horner3) >"$T/inst.run" 2>"$T/inst.err"
rc=$?
# The reference: the same run by the binary under test in the source tree.
SHADESIM_HOME="$root" "$S" run horner3 >"$T/tree.run" 2>/dev/null
check installed_run_from_root [ $rc -eq 0 -a ! -s "$T/inst.err" ]
check installed_run_same_output cmp -s "$T/inst.run" "$T/tree.run"
nrows=$(grep -c '^[^#]' vectors/horner3.vec)
check installed_run_default_vectors grep -q "^vectors $nrows," "$T/inst.run"

# SHADESIM_HOME wins: a folder with a shorter horner3.vec (the header and
# the first 10 rows of the real one).
mkdir -p "$T/home/vectors"
awk '/^#/ || n < 10 { print } !/^#/ { n++ }' vectors/horner3.vec >"$T/home/vectors/horner3.vec"
(cd / && SHADESIM_HOME="$T/home" "$P/bin/shadesim" run horner3) >"$T/home.run" 2>&1
check home_overrides_install grep -q '^vectors 10,' "$T/home.run"
# ... and it is the only place looked at: an empty one is an error.
mkdir -p "$T/empty"
(cd / && SHADESIM_HOME="$T/empty" "$P/bin/shadesim" run horner3) >"$T/empty.out" 2>"$T/empty.err"
rc=$?
check home_missing_exit_2 [ $rc -eq 2 -a "$(wc -l <"$T/empty.err")" -eq 1 ]
check home_missing_names_path grep -q "$T/empty/vectors/horner3.vec" "$T/empty.err"

# A lone copy of the binary with no data beside it: one line, status 2,
# naming where the vectors were expected.
mkdir -p "$T/lone/bin"
cp "$P/bin/shadesim" "$T/lone/bin/"
(cd / && env -u SHADESIM_HOME "$T/lone/bin/shadesim" run horner3) >"$T/lone.out" 2>"$T/lone.err"
rc=$?
check lone_binary_exit_2 [ $rc -eq 2 -a "$(wc -l <"$T/lone.err")" -eq 1 ]
check lone_binary_names_share grep -q "$T/lone/share/shadesim/vectors/horner3.vec" "$T/lone.err"
check lone_binary_says_install grep -q "install with make install" "$T/lone.err"
# The same binary in a source tree (a Makefile and units/ one up from its
# bin/) whose vectors/ lacks the file: it names the tree's vectors/ and
# make vectors, not the install's share/ (which it named)
mkdir -p "$T/tree/bin" "$T/tree/units" "$T/tree/vectors" && : >"$T/tree/Makefile"
cp "$P/bin/shadesim" "$T/tree/bin/"
(cd / && env -u SHADESIM_HOME "$T/tree/bin/shadesim" run horner3) >"$T/tree.out" 2>"$T/tree.err"
rc=$?
[ $rc -eq 2 ] && [ "$(wc -l <"$T/tree.err")" -eq 1 ] && grep -q "^shadesim: $T/tree/vectors/horner3.vec: .*make vectors" "$T/tree.err" \
    && ok source_tree_names_make_vectors || fail source_tree_names_make_vectors "exit $rc: $(cat "$T/tree.err")"
# --vectors still works without any data folder.
(cd / && env -u SHADESIM_HOME "$T/lone/bin/shadesim" run horner3 --vectors "$root/vectors/horner3.vec") >"$T/lonev.run" 2>/dev/null
check lone_binary_with_vectors cmp -s "$T/lonev.run" "$T/tree.run"

# ---- --version, help VERB ----
v=$("$P/bin/shadesim" --version)
check version_line [ "$(printf '%s\n' "$v" | wc -l)" -eq 1 ]
case "$v" in "shadesim $(cat VERSION)"*) ok version_from_VERSION ;; *) fail version_from_VERSION "got '$v'" ;; esac
"$S" help run >"$T/h1" 2>&1; r1=$?
"$S" run --help >"$T/h2" 2>&1
if [ $r1 -eq 0 ] && cmp -s "$T/h1" "$T/h2"; then ok help_verb_is_verb_help; else fail help_verb_is_verb_help; fi
"$S" help no_such_verb >/dev/null 2>"$T/h3"; r3=$?
check help_unknown_verb [ $r3 -eq 2 -a "$(wc -l <"$T/h3")" -eq 1 ]

# ---- the man page: every verb of --help, with its own help text ----
man1="$P/share/man/man1/shadesim.1"
check man_header [ "$(head -1 "$man1" | cut -c1-15)" = ".TH SHADESIM 1 " ]
verbs=$("$S" --help | sed -n '/^verbs:/,/^$/s/^  \([a-z0-9_]*\) .*/\1/p')
missing=
for vb in $verbs; do
    # the first line of the verb's help, as roff writes it (- as \-)
    first=$("$S" "$vb" --help | head -1 | sed 's/-/\\-/g')
    grep -qF "$first" "$man1" || missing="$missing $vb"
done
check man_every_verb [ -n "$verbs" -a -z "$missing" ]
[ -n "$missing" ] && echo "  missing from the man page:$missing"
if command -v man >/dev/null 2>&1 && man -l "$man1" >"$T/man.txt" 2>"$T/man.err" && [ -s "$T/man.txt" ]; then
    check man_renders grep -q 'SHADESIM(1)' "$T/man.txt"
    check man_renders_cleanly [ ! -s "$T/man.err" ]
else
    echo "skip ${PREFIX}man_renders: man not installed (checked the roff header only)"
fi
"$S" --man >"$T/man2" 2>/dev/null
check man_deterministic cmp -s "$man1" "$T/man2"

# ---- uninstall ----
env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make -s --no-print-directory uninstall PREFIX="$P" >/dev/null 2>&1
check uninstall_removes [ ! -e "$P/bin/shadesim" -a ! -e "$P/share/shadesim" -a ! -e "$man1" ]
# ... and the folders it made, now empty (the prefix itself too); a folder
# that holds something else stays.
check uninstall_removes_empty_folders [ ! -e "$P" ]
mkdir -p "$T/keep/bin" "$T/keep/share/doc"
: >"$T/keep/bin/other-tool"
env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make -s --no-print-directory install INSTALL_BIN="$S" PREFIX="$T/keep" \
    >/dev/null 2>&1
env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make -s --no-print-directory uninstall PREFIX="$T/keep" >/dev/null 2>&1
check uninstall_keeps_other_files [ -f "$T/keep/bin/other-tool" -a ! -e "$T/keep/bin/shadesim" -a ! -e "$T/keep/share" ]
