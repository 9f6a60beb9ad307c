#!/bin/sh
# cli_suggest.sh - a mistyped verb, unit, option or built-in scene is
# refused (exit 2, one line) with the nearest name suggested; a word near
# nothing gets no suggestion; an unknown scene name lists the built-ins.
. tests/lib_cli.sh
no_leak_check   # (lib_cli.sh: the same verbs over and over)
PREFIX=cli_suggest.

# suggest NAME WANT CMD...: exit 2, one line, containing WANT.
suggest() {
    sname=$1 swant=$2; shift 2
    expect "$sname" 2 "$@" || return
    grep -qF -- "$swant" "$T/err" && ok "${sname}_says" || fail "${sname}_says" "$(cat "$T/err")"
}
suggest verb_typo "did you mean 'run'?" "$S" rnu horner3
suggest unit_typo "did you mean 'horner3'?" "$S" run horner
suggest unit_typo_list "did you mean 'div3'?" "$S" list dvi3
suggest option_typo "did you mean '--width'? see shadesim run --help" "$S" run horner3 --widht 12
suggest option_typo_value_form "did you mean '--width'?" "$S" run horner3 --widht=12
suggest sweep_option_typo "did you mean '--target-error'?" "$S" sweep horner3 --widths 8:9 --target-eror 1e-3
suggest scene_typo "did you mean 'sphere'? built-in: face, sphere, torus" "$S" scene sphre
suggest scene_unknown_lists_builtins "no built-in scene or scene file 'cube' (built-in: face, sphere, torus)" "$S" scene cube
suggest scene_key_typo 'did you mean "fov"' "$S" scene sphere --set fvo=30
# factor speaks as the other verbs do (it had "--resl: unknown option" and
# no suggestion for a BRDF)
suggest factor_option_typo "shadesim: factor: unknown option '--resl' (did you mean '--res'? see shadesim factor --help)" "$S" factor ward --resl 3
suggest factor_brdf_typo "shadesim: factor: unknown BRDF 'wardd' (did you mean 'ward'? one of blinn, ct, ward, ward-aniso)" "$S" factor wardd
suggest factor_option_first "shadesim: factor: which BRDF?" "$S" factor --res 8
# Far from everything: no suggestion.
expect option_far 2 "$S" run horner3 --zzzzzzzz
grep -q "did you mean" "$T/err" && fail option_far_no_suggestion "$(cat "$T/err")" || ok option_far_no_suggestion
expect verb_far 2 "$S" qqqqqqqq
grep -q "did you mean" "$T/err" && fail verb_far_no_suggestion "$(cat "$T/err")" || ok verb_far_no_suggestion
# A scene path that is a file name (has a dot or slash) keeps the file error.
expect scene_missing_file 2 "$S" scene "$T/none.scn"
grep -q "cannot open" "$T/err" && ok scene_missing_file_says_cannot_open || fail scene_missing_file_says_cannot_open "$(cat "$T/err")"
