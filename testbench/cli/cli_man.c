/* cli_man.c - shadesim(1) from the verb table and each verb's --help.
 *
 * Each verb's help is captured by running the verb with --help while file
 * descriptor 1 points at a temporary file: the page quotes the very text
 * `shadesim VERB --help` prints, with nothing kept in two places.
 */
#include "testbench/cli/cli_man.h"
#include "testbench/cli/cli.h"
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* One line of plain text as roff: backslashes escaped, hyphens made
 * minus signs (so options copy and search as typed), a leading dot or
 * quote protected from being read as a request. */
static void roff_line(FILE *f, const char *s, size_t n)
{
    if (n && (s[0] == '.' || s[0] == '\'')) fputs("\\&", f);
    for (size_t i = 0; i < n; i++) {
        if (s[i] == '\\') fputs("\\e", f);
        else if (s[i] == '-') fputs("\\-", f);
        else fputc(s[i], f);
    }
    fputc('\n', f);
}

static void roff_text(FILE *f, const char *s)
{
    while (*s) {
        const char *nl = strchr(s, '\n');
        size_t n = nl ? (size_t)(nl - s) : strlen(s);
        roff_line(f, s, n);
        s += n + (nl != NULL);
    }
}

/* The text a verb prints for --help (malloc'd; a note when it prints
 * none), or NULL when it cannot be captured. */
static char *verb_help(const cli_verb *v)
{
    FILE *tmp = tmpfile();
    if (!tmp) return NULL;
    fflush(stdout);
    int saved = dup(1);
    if (saved < 0 || dup2(fileno(tmp), 1) < 0) {
        if (saved >= 0) close(saved);
        fclose(tmp);
        return NULL;
    }
    char a0[32], a1[] = "--help";
    snprintf(a0, sizeof a0, "%s", v->name);
    char *argv[] = { a0, a1, NULL };
    (void)v->fn(2, argv);
    fflush(stdout);
    dup2(saved, 1);
    close(saved);
    char *buf = NULL;
    long len = ftell(tmp);
    if (len > 0 && (buf = malloc((size_t)len + 1))) {
        rewind(tmp);
        size_t got = fread(buf, 1, (size_t)len, tmp);
        buf[got] = 0;
    } else if (len <= 0) {
        static const char none[] = "(this verb prints no help text)\n";
        if ((buf = malloc(sizeof none))) memcpy(buf, none, sizeof none);
    }
    fclose(tmp);
    return buf;
}

int cli_man(FILE *f, const char *version)
{
    /* Capture every help first: f may be stdout. */
    size_t nv = 0;
    while (cli_verbs[nv].name) nv++;
    char **help = calloc(nv ? nv : 1, sizeof *help);
    if (!help) return -1;
    for (size_t i = 0; i < nv; i++)
        if (!(help[i] = verb_help(&cli_verbs[i]))) {
            fprintf(stderr, "shadesim: --man: cannot capture the help of '%s'\n", cli_verbs[i].name);
            for (size_t j = 0; j < i; j++) free(help[j]);
            free(help);
            return -1;
        }

    fprintf(f, ".TH SHADESIM 1 \"\" \"shadesim %s\" \"User Commands\"\n", version);
    fputs(".SH NAME\nshadesim \\- cycle\\-accurate fixed\\-point simulator of shading hardware\n"
          ".SH SYNOPSIS\n.B shadesim\n.I VERB\n[\\fIoptions\\fR]\n.br\n"
          ".B shadesim\n.BR \\-\\-help \" | \" \\-\\-version \" | \" \\-\\-man\n.br\n"
          ".B shadesim help\n.I VERB\n"
          ".SH DESCRIPTION\n", f);
    roff_text(f,
        "shadesim simulates, clock by clock and in configurable fixed-point widths, the\n"
        "datapaths of published shading hardware: polynomial interpolation of intensity\n"
        "along raster spans (coefficient networks, a divide-by-3 shift network, a Horner\n"
        "datapath) and low-cost approximations of the Cook-Torrance, Ward and Schlick\n"
        "reflection models. It drives each unit with golden vectors from a\n"
        "double-precision reference and reports cycles, area, bits and error, checks every\n"
        "output against an error bound derived from the formats, renders scenes through\n"
        "the simulated hardware, and sets the papers' numerical claims beside what it\n"
        "measures.");
    fputs(".SH VERBS\n", f);
    for (size_t i = 0; i < nv; i++) {
        fprintf(f, ".TP\n.B %s\n", cli_verbs[i].name);
        roff_text(f, cli_verbs[i].summary);
    }
    fputs(".SH OPTIONS OF EACH VERB\n", f);
    for (size_t i = 0; i < nv; i++) {
        fprintf(f, ".SS \"shadesim %s\"\n.nf\n", cli_verbs[i].name);
        roff_text(f, help[i]);
        fputs(".fi\n", f);
        free(help[i]);
    }
    free(help);
    fputs(".SH EXIT STATUS\n", f);
    roff_text(f,
        "0: success. 1: an error bound or a target was exceeded, or the simulation\n"
        "failed. 2: bad usage or bad input, with one line on standard error naming the\n"
        "file and line or the option, and the problem. 3: out of memory (one line on\n"
        "standard error; no output file is left half written).");
    fputs(".SH ENVIRONMENT\n.TP\n.B SHADESIM_HOME\n", f);
    roff_text(f,
        "A folder holding vectors/UNIT.vec, the default golden vectors. When set, it is\n"
        "the only place they are looked for.");
    fputs(".SH FILES\n", f);
    roff_text(f,
        "Without SHADESIM_HOME, the default vectors of a unit are looked for in this\n"
        "order: PREFIX/share/shadesim/vectors/ beside an installed PREFIX/bin/shadesim;\n"
        "vectors/ one folder above the binary (a binary built in the source tree);\n"
        "vectors/ in the current folder. --vectors FILE (or - for standard input) gives\n"
        "them explicitly.");
    fputs(".SH OUTPUT FILES\n", f);
    roff_text(f,
        "A regular output file is written under a temporary name and renamed when\n"
        "complete, so it is never half-written; a device, FIFO or symbolic link is\n"
        "written through, not replaced (a link keeps pointing at the same file, which\n"
        "gets the bytes once the output is complete); - is standard output where a\n"
        "verb allows it. The files of one run (sweep, scene, report, factor,\n"
        "stability, verilog) appear together or, on a failure, not at all.\n"
        "The same inputs give the same bytes: no time stamps, no timings.");
    fputs(".SH SEE ALSO\n", f);
    roff_text(f,
        "gtkwave(1) for the waveforms of run --vcd. The documentation in share/doc/shadesim\n"
        "(docs/ in the source tree): cli.md, vectors.md, metrics.md, units.md,\n"
        "references.md for the papers the units come from.");
    return ferror(f) ? -1 : 0;
}
