/* test_dp_fuzz.c - the datapath reader (tb_netlist_load with datapath
 * NAME, docs/datapaths.md) on mutants of the example files: bytes
 * replaced, inserted or deleted, lines deleted, doubled or swapped, words
 * swapped between lines, numbers made extreme. Every mutant is read; one
 * the reader accepts is built, bounded, run on a few generated vectors and
 * exported as Verilog, at its own width and two others. Nothing may crash,
 * leak or hang (the suite runs this under ASan+UBSan too); a mutant refused
 * must say FILE:LINE or FILE: in one line. Deterministic (a fixed seed).
 *   DP_FUZZ_N=N           mutants (default 400)
 *   DP_FUZZ_SECONDS=S     mutants until S seconds have passed (make
 *                         fuzz-datapath: 300 under the sanitizers)
 */
#include "tests/tst.h"
#include "testbench/tb_netlist.h"
#include "testbench/tb_netlist_int.h"
#include "testbench/tb_verilog.h"
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* the examples, and a built-in unit's file (netlist mschlick --datapath):
 * ideal unit=, its own handshake, fn=verilog texts with a case */
static const char *const examples[] = { "examples/horner3.dp", "examples/fir4.dp", "examples/dot3.dp",
                                        "examples/fir4_pipe.dp", "tests/data/mschlick.dp" };
#define NEX 5
static char *text[NEX];
static size_t len[NEX];

static char *slurp(const char *path, size_t *n)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    char *buf = malloc(1 << 16);
    *n = buf ? fread(buf, 1, (1 << 16) - 1, f) : 0;
    fclose(f);
    if (buf) buf[*n] = 0;
    return buf;
}

/* The mutant of text t (len n) into out (cap bytes): its length. */
static size_t mutate(vec_rng *r, const char *t, size_t n, char *out, size_t cap)
{
    static const char pieces[][12] = { "W", "(W-", ")", "=", ",", ".", "-", "+", "*", "/", "0", "1", "64", "65",
                                       "-1", "1e308", "clk", "step", "in_valid", "y", "rg", "sm", "x0", "\n", " ",
                                       "#", "\"", "s", "u", ":sat", "sqrt(", "min(", "clocks=", "99999999999",
                                       "%t_", "%0", "[", "]", "{", "}", "?", "case", "$signed(", "<<", "16'h" };
    memcpy(out, t, n);
    int k = 1 + (int)(vec_rng_next(r) % 4);
    for (int m = 0; m < k && n > 2; m++) {
        size_t a = vec_rng_next(r) % n, b = vec_rng_next(r) % n;
        if (a > b) { size_t s = a; a = b; b = s; }
        switch (vec_rng_next(r) % 7) {
        case 0: out[a] = (char)(32 + vec_rng_next(r) % 95); break;                  /* a byte */
        case 1: {                                                                    /* a piece inserted */
            const char *p = pieces[vec_rng_next(r) % (sizeof pieces / sizeof pieces[0])];
            size_t pl = strlen(p);
            if (n + pl >= cap) break;
            memmove(out + a + pl, out + a, n - a);
            memcpy(out + a, p, pl);
            n += pl;
            break;
        }
        case 2:                                                                      /* a span deleted */
            if (b - a > 40) b = a + 40;
            memmove(out + a, out + b, n - b);
            n -= b - a;
            break;
        case 3: {                                                                    /* a line deleted */
            while (a > 0 && out[a - 1] != '\n') a--;
            size_t e = a;
            while (e < n && out[e] != '\n') e++;
            if (e < n) e++;
            memmove(out + a, out + e, n - e);
            n -= e - a;
            break;
        }
        case 4: {                                                                    /* a line doubled */
            while (a > 0 && out[a - 1] != '\n') a--;
            size_t e = a;
            while (e < n && out[e] != '\n') e++;
            if (e < n) e++;
            if (n + (e - a) >= cap) break;
            memmove(out + e + (e - a), out + e, n - e);
            memcpy(out + e, out + a, e - a);
            n += e - a;
            break;
        }
        case 5: {                                                                    /* two bytes swapped */
            char c = out[a];
            out[a] = out[b];
            out[b] = c;
            break;
        }
        default: {                                                                   /* a word copied over another */
            size_t ws = a, we = a, vs = b, ve = b;
            while (we < n && out[we] != ' ' && out[we] != '\n') we++;
            while (ve < n && out[ve] != ' ' && out[ve] != '\n') ve++;
            size_t wl = we - ws, vl = ve - vs;
            if (n - vl + wl >= cap || wl > 60) break;
            char w[64];
            memcpy(w, out + ws, wl);
            memmove(out + vs + wl, out + ve, n - ve);
            memcpy(out + vs, w, wl);
            n = n - vl + wl;
            break;
        }
        }
    }
    return n;
}

static long accepted, refused;

/* One mutant through everything a verb does with a file. */
static void exercise(const char *t, size_t n, const char *name)
{
    unit_cfg cfg;
    unit_fmts fm;
    char err[1400] = "";
    const unit_desc *u = nl_load_text(t, n, name, &cfg, &fm, err, sizeof err);
    if (!u) {
        refused++;
        size_t nl = strlen(name);
        TST_CHECK(!strncmp(err, name, nl) && err[nl] == ':' && !strchr(err, '\n'), "refused without FILE:LINE: %s", err);
        return;
    }
    accepted++;
    if (!tb_datapath_is(u)) { tb_netlist_free(u); return; }
    int widths[3] = { cfg.width, 9, 20 };
    for (int k = 0; k < 3; k++) {
        unit_cfg c = cfg;
        c.width = widths[k];
        unit_fmts f;
        if (tb_formats(u, &c, NULL, 0, &f, err, sizeof err)) continue;
        for (int i = 0; i < u->nsigs; i++)
            TST_CHECK(f.f[i].width >= 1 && f.f[i].width <= 64, "width %d: %s has a format of %d bits", c.width,
                      u->sigs[i].name, f.f[i].width);
        if (tst_failed_checks) return;
        double b[UNIT_MAX_IO];
        unit_bound(u, &c, &f, b);
        vec_set vs;
        if (tb_make_vectors(u, &c, 8, 3, &vs, err, sizeof err)) { vec_set_free(&vs); continue; }
        tb_result r;
        tb_opts o = { 0 };
        tb_run(u, &c, &f, &vs, &o, &r, err, sizeof err);   /* a design may fail to run: no output in time */
        tb_result_free(&r);                                /* what tb_run allocated, either way */
        free(tb_verilog_module_text(u, &c, &f, SIM_VRESET_SYNC, err, sizeof err));
        vec_set_free(&vs);
    }
    tb_netlist_free(u);
}

static void t_mutants(void)
{
    for (int i = 0; i < NEX; i++)
        if (!(text[i] = slurp(examples[i], &len[i]))) { TST_SKIP("%s: not found (run from the source tree)", examples[i]); return; }
    /* the examples themselves are accepted */
    for (int i = 0; i < NEX; i++) {
        long a = accepted;
        exercise(text[i], len[i], examples[i]);
        TST_CHECK(accepted == a + 1, "%s refused", examples[i]);
    }
    const char *e = getenv("DP_FUZZ_N"), *s = getenv("DP_FUZZ_SECONDS");
    long n = e ? atol(e) : s ? -1 : 400;
    double secs = s ? atof(s) : 0;
    time_t t0 = time(NULL);
    vec_rng r = { 12345 };
    static char out[1 << 17];
    long k = 0;
    for (; n < 0 ? difftime(time(NULL), t0) < secs : k < n; k++) {
        int i = (int)(vec_rng_next(&r) % NEX);
        size_t m = mutate(&r, text[i], len[i], out, sizeof out);
        exercise(out, m, "mutant.dp");
        if (tst_failed_checks) { printf("  mutant %ld of %s:\n%.*s\n", k, examples[i], (int)m, out); break; }
    }
    printf("  %ld mutants: %ld accepted, %ld refused with FILE:LINE\n", k, accepted - NEX, refused);
    TST_CHECK(accepted > NEX && refused > 0, "the mutants should be both accepted and refused");
    for (int i = 0; i < NEX; i++) free(text[i]);
}

int main(void)
{
    TST_RUN(t_mutants);
    TST_EXIT();
}
