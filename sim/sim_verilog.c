/* sim_verilog.c - a built design as Verilog-2001 (see sim_verilog.h).
 *
 * Every intermediate is an explicitly sized bit vector: operands are
 * sign- or zero-extended by concatenation to the width of the exact
 * result, so no expression depends on Verilog's width and signedness
 * rules (and `verilator -Wall` has no width warning to give). Products
 * are the one exception: `$signed(a) * $signed(b)` on the operands at
 * their own widths, which the product's width extends as signed (the
 * form synthesis builds a wa x wb multiplier from).
 */
#include "sim/sim_verilog.h"
#include "sim/sim_prim.h"
#include <ctype.h>
#include <stdlib.h>
#include <string.h>

typedef struct vgen {
    FILE *f;
    const sim_ctx *c;
    const sim_scope *sc;
    char **name;            /* by signal index: Verilog name, NULL if not ours */
    uint32_t nsig;
    sim_vreset reset;
    char *err;
    size_t errlen;
} vgen;

static int in_scope(const sim_signal *s, const sim_scope *sc)
{
    for (const sim_scope *p = s->scope; p; p = p->parent) if (p == sc) return 1;
    return 0;
}

static const char *const keywords[] = {
    "always", "and", "assign", "begin", "buf", "case", "casex", "casez", "default", "defparam",
    "else", "end", "endcase", "endfunction", "endmodule", "endtask", "event", "for", "force",
    "forever", "function", "generate", "genvar", "if", "initial", "inout", "input", "integer",
    "localparam", "module", "nand", "negedge", "nor", "not", "or", "output", "parameter",
    "posedge", "real", "reg", "repeat", "signed", "task", "time", "tri", "unsigned", "wait",
    "while", "wire", "xor", "xnor", "clk", "rst", "bit", "logic", "int", "byte", "do", "final",
    NULL };

static int is_keyword(const char *s)
{
    for (int i = 0; keywords[i]; i++) if (!strcmp(s, keywords[i])) return 1;
    return 0;
}

/* Flattened name below sc: scopes and name joined by '_', other characters
 * made '_', no "__" (reserved for the generator's own wires). */
static void flat_name(const sim_signal *s, const sim_scope *sc, char *buf, size_t len)
{
    const sim_scope *chain[16];
    int n = 0;
    for (const sim_scope *p = s->scope; p && p != sc && n < 16; p = p->parent) chain[n++] = p;
    char raw[256];
    size_t at = 0;
    raw[0] = 0;
    while (n-- > 0 && at + 2 < sizeof raw) {
        int w = snprintf(raw + at, sizeof raw - at, "%s_", chain[n]->name);
        if (w < 0) break;
        at += (size_t)w < sizeof raw - at ? (size_t)w : sizeof raw - at - 1;
    }
    snprintf(raw + at, sizeof raw - at, "%s", s->name);
    size_t o = 0;
    for (const char *p = raw; *p && o + 1 < len; p++) {
        char ch = isalnum((unsigned char)*p) ? *p : '_';
        if (ch == '_' && o && buf[o - 1] == '_') continue;
        buf[o++] = ch;
    }
    while (o && buf[o - 1] == '_') o--;
    buf[o] = 0;
    if (!o || isdigit((unsigned char)buf[0])) {
        memmove(buf + 2, buf, o + 1 < len - 2 ? o + 1 : len - 2);
        buf[0] = 's'; buf[1] = '_';
        buf[len - 1] = 0;
    }
}

static int name_taken(const vgen *g, const char *s)
{
    for (uint32_t i = 0; i < g->nsig; i++) if (g->name[i] && !strcmp(g->name[i], s)) return 1;
    return 0;
}

static const char *N(const vgen *g, const sim_signal *s) { return g->name[s->index]; }

/* Bits of a raw pattern as Verilog hex literal of width w. */
static void lit(char *buf, size_t len, int w, int64_t raw)
{
    uint64_t m = w >= 64 ? UINT64_MAX : (((uint64_t)1 << w) - 1);
    snprintf(buf, len, "%d'h%llx", w, (unsigned long long)((uint64_t)raw & m));
}

/* Width of a signal's value as a signed number. */
static int sw(const sim_signal *s) { return s->fmt.width + !s->fmt.is_signed; }

/* Expression: signal s as a signed value of width T (>= sw(s)), times 2^sh
 * (sh >= 0 zero bits appended): T includes the appended bits. */
static void ext(char *buf, size_t len, const vgen *g, const sim_signal *s, int T, int sh)
{
    int w = s->fmt.width, pad = T - sh - w;
    char fill[160] = "", tail[32] = "";
    if (pad > 0) {
        if (s->fmt.is_signed) snprintf(fill, sizeof fill, "{%d{%s[%d]}}, ", pad, N(g, s), w - 1);
        else snprintf(fill, sizeof fill, "%d'b0, ", pad);
    }
    if (sh > 0) snprintf(tail, sizeof tail, ", %d'b0", sh);
    if (!fill[0] && !tail[0]) snprintf(buf, len, "%s", N(g, s));
    else snprintf(buf, len, "{%s%s%s}", fill, N(g, s), tail);
}

/* Quantize the signed exact value in wire `src` (width SW, src_f fraction
 * bits) into y's format with modes r, o; assign to `dst` (width y.width).
 * pre: unique prefix for the wires made here. */
static void quant(vgen *g, const char *pre, const char *src, int SW, int src_f, sim_fmt y,
                  sim_round r, sim_ovf o, const char *dst)
{
    FILE *f = g->f;
    int W = y.width, k = src_f - y.fbits;
    char cur[200];
    int QW = SW;
    snprintf(cur, sizeof cur, "%s", src);
    if (k > 0) {
        /* at least k + 1 bits, so that the first dropped bit and the sign exist */
        if (SW < k + 1) {
            fprintf(f, "    wire [%d:0] %s__x = {{%d{%s[%d]}}, %s};\n", k, pre, k + 1 - SW, src, SW - 1, src);
            snprintf(cur, sizeof cur, "%s__x", pre);
            SW = k + 1;
        }
        int FW = SW - k;
        if (r == SIM_RND_TRUNC) {
            fprintf(f, "    wire [%d:0] %s__r = %s[%d:%d];\n", FW - 1, pre, cur, SW - 1, k);
            QW = FW;
        } else {
            if (r == SIM_RND_HALF_UP)
                fprintf(f, "    wire %s__up = %s[%d];\n", pre, cur, k - 1);
            else if (k >= 2)
                fprintf(f, "    wire %s__up = %s[%d] & ((|%s[%d:0]) | %s[%d]);\n", pre, cur, k - 1, cur, k - 2, cur, k);
            else
                fprintf(f, "    wire %s__up = %s[%d] & %s[%d];\n", pre, cur, k - 1, cur, k);
            /* floor plus the increment, one bit wider: cannot overflow */
            fprintf(f, "    wire [%d:0] %s__r = {%s[%d], %s[%d:%d]} + {%d'b0, %s__up};\n",
                    FW, pre, cur, SW - 1, cur, SW - 1, k, FW, pre);
            QW = FW + 1;
        }
        snprintf(cur, sizeof cur, "%s__r", pre);
    } else if (k < 0) {
        fprintf(f, "    wire [%d:0] %s__r = {%s, %d'b0};\n", SW - k - 1, pre, cur, -k);
        snprintf(cur, sizeof cur, "%s__r", pre);
        QW = SW - k;
    }
    /* cur: signed, QW bits, y's fraction bits. Wrap: its low W bits. */
    char wrap[512];
    if (QW >= W) snprintf(wrap, sizeof wrap, "%s[%d:0]", cur, W - 1);
    else snprintf(wrap, sizeof wrap, "{{%d{%s[%d]}}, %s}", W - QW, cur, QW - 1, cur);
    /* Fits: signed, the bits from W-1 up are all copies of the sign;
     * unsigned, the bits from W up (sign included) are all 0. */
    int lo_bit = y.is_signed ? W - 1 : W;
    int may_ovf = y.is_signed ? QW > W : 1;
    if (o == SIM_OVF_WRAP || !may_ovf) {
        fprintf(f, "    assign %s = %s;\n", dst, wrap);
        return;
    }
    if (lo_bit > QW - 1) {
        /* unsigned target wider than the value: only negatives overflow */
        fprintf(f, "    assign %s = %s[%d] ? %d'b0 : %s;\n", dst, cur, QW - 1, W, wrap);
        return;
    }
    char lo[40], hi[40];
    if (y.is_signed) { snprintf(lo, sizeof lo, "{1'b1, %d'b0}", W - 1); snprintf(hi, sizeof hi, "{1'b0, {%d{1'b1}}}", W - 1); }
    else { snprintf(lo, sizeof lo, "%d'b0", W); snprintf(hi, sizeof hi, "{%d{1'b1}}", W); }
    if (W == 1 && y.is_signed) { snprintf(lo, sizeof lo, "1'b1"); snprintf(hi, sizeof hi, "1'b0"); }
    if (y.is_signed)
        fprintf(f, "    wire %s__ok = (&%s[%d:%d]) | ~(|%s[%d:%d]);\n", pre, cur, QW - 1, lo_bit, cur, QW - 1, lo_bit);
    else
        fprintf(f, "    wire %s__ok = ~(|%s[%d:%d]);\n", pre, cur, QW - 1, lo_bit);
    fprintf(f, "    assign %s = %s__ok ? %s : (%s[%d] ? %s : %s);\n", dst, pre, wrap, cur, QW - 1, lo, hi);
}

/* Quantize signal x (exact as it is) into dst of format y. */
static void quant_sig(vgen *g, const char *pre, const sim_signal *x, sim_fmt y, sim_round r, sim_ovf o,
                      const char *dst)
{
    char e[300];
    int T = sw(x);
    ext(e, sizeof e, g, x, T, 0);
    sim_fmt xf = x->fmt;
    if (xf.fbits == y.fbits && (xf.is_signed == y.is_signed ? xf.width <= y.width : !xf.is_signed && xf.width < y.width)) {
        /* nothing to round, always fits: extend */
        char s[300];
        ext(s, sizeof s, g, x, y.width, 0);
        fprintf(g->f, "    assign %s = %s;\n", dst, s);
        return;
    }
    fprintf(g->f, "    wire [%d:0] %s__e = %s;\n", T - 1, pre, e);
    char src[200];
    snprintf(src, sizeof src, "%s__e", pre);
    quant(g, pre, src, T, x->fmt.fbits, y, r, o, dst);
}

static int64_t canon(uint64_t v, sim_fmt f)
{
    return sim_fx_canon((int64_t)v, f);
}

/* A logic element's own Verilog text (sim_logic_verilog), placeholders
 * replaced. */
static void emit_text(vgen *g, const sim_signal *y, const sim_prim_info *in)
{
    const char *nm = N(g, y);
    fputs("    ", g->f);
    for (const char *p = in->verilog; *p; p++) {
        if (*p == '%' && p[1] == 'y') { fputs(nm, g->f); p++; }
        else if (*p == '%' && p[1] == 't') { fprintf(g->f, "%s_", nm); p++; }
        else if (*p == '%' && p[1] >= '0' && p[1] < '0' + in->n) { fputs(N(g, in->in[p[1] - '0']), g->f); p++; }
        else if (*p == '\n') fputs(p[1] ? "\n    " : "\n", g->f);
        else fputc(*p, g->f);
    }
    if (!*in->verilog || in->verilog[strlen(in->verilog) - 1] != '\n') fputc('\n', g->f);
}

/* A logic element as a table over its input bits (or its own text). */
static int emit_logic(vgen *g, const sim_signal *y, const sim_prim_info *in, const sim_signal *clk)
{
    (void)clk;
    FILE *f = g->f;
    int bits = 0;
    for (int i = 0; i < in->n; i++) bits += in->in[i]->fmt.width;
    const char *nm = N(g, y);
    if (in->verilog && bits > 8) { emit_text(g, y, in); return 0; }
    if (bits > SIM_VERILOG_MAX_LOGIC_BITS) {
        snprintf(g->err, g->errlen, "logic element %s has %d input bits: too many to tabulate (at most %d)",
                 y->name, bits, SIM_VERILOG_MAX_LOGIC_BITS);
        return -1;
    }
    size_t ncomb = (size_t)1 << bits;
    uint64_t *out = malloc(ncomb * sizeof *out);
    if (!out) { snprintf(g->err, g->errlen, "out of memory"); return -1; }
    uint64_t ymask = y->fmt.width >= 64 ? UINT64_MAX : (((uint64_t)1 << y->fmt.width) - 1);
    for (size_t k = 0; k < ncomb; k++) {
        int64_t v[8];
        int at = bits;
        for (int i = 0; i < in->n; i++) {   /* in[0] is the most significant field */
            int w = in->in[i]->fmt.width;
            at -= w;
            v[i] = canon((k >> at) & ((1ull << w) - 1), in->in[i]->fmt);
        }
        out[k] = (uint64_t)in->fn(v, in->user) & ymask;
    }
    /* the most frequent value is the default */
    uint64_t dflt = out[0];
    size_t best = 0;
    for (size_t k = 0; k < ncomb && k < 4096; k++) {
        size_t cnt = 0;
        for (size_t j = 0; j < ncomb; j++) cnt += out[j] == out[k];
        if (cnt > best) { best = cnt; dflt = out[k]; }
    }
    char l[64];
    lit(l, sizeof l, y->fmt.width, (int64_t)dflt);
    if (best == ncomb) {
        fprintf(f, "    assign %s = %s;   // constant over all its inputs\n", nm, l);
        free(out);
        return 0;
    }
    fprintf(f, "    reg [%d:0] %s__t;\n    always @* begin\n        case ({", y->fmt.width - 1, nm);
    for (int i = 0; i < in->n; i++) fprintf(f, "%s%s", i ? ", " : "", N(g, in->in[i]));
    fprintf(f, "})\n");
    for (size_t k = 0; k < ncomb; k++) {
        if (out[k] == dflt) continue;
        char kl[64], vl[64];
        lit(kl, sizeof kl, bits, (int64_t)k);
        lit(vl, sizeof vl, y->fmt.width, (int64_t)out[k]);
        fprintf(f, "            %s: %s__t = %s;\n", kl, nm, vl);
    }
    fprintf(f, "            default: %s__t = %s;\n        endcase\n    end\n    assign %s = %s__t;\n", nm, l, nm, nm);
    free(out);
    return 0;
}

static int emit_mux(vgen *g, const sim_signal *y, const sim_prim_info *in, const sim_signal *clk)
{
    (void)clk;
    FILE *f = g->f;
    const char *nm = N(g, y);
    int same = 1;
    for (int i = 1; i < in->n; i++)
        same &= in->in[i]->fmt.is_signed == in->in[0]->fmt.is_signed
             && in->in[i]->fmt.ibits == in->in[0]->fmt.ibits && in->in[i]->fmt.fbits == in->in[0]->fmt.fbits;
    /* Inputs of one format: select, then quantize once (what the simulator
     * computes too); else quantize each input, then select. */
    sim_fmt mf = same && in->n ? in->in[0]->fmt : y->fmt;
    int mw = mf.width;
    char pre[300];
    if (!same)
        for (int i = 0; i < in->n; i++) {
            snprintf(pre, sizeof pre, "%s__i%d", nm, i);
            fprintf(f, "    wire [%d:0] %s;\n", y->fmt.width - 1, pre);
            quant_sig(g, pre, in->in[i], y->fmt, in->r, in->o, pre);
        }
    const sim_signal *sel = in->c;
    int64_t selmax = sim_fmt_raw_max(sel->fmt);
    fprintf(f, "    reg [%d:0] %s__m;\n    always @* begin\n        case (%s)\n", mw - 1, nm, N(g, sel));
    for (int i = 0; i < in->n && i <= selmax; i++) {
        char kl[64];
        lit(kl, sizeof kl, sel->fmt.width, i);
        if (same) fprintf(f, "            %s: %s__m = %s;\n", kl, nm, N(g, in->in[i]));
        else fprintf(f, "            %s: %s__m = %s__i%d;\n", kl, nm, nm, i);
    }
    /* out-of-range select: 0 (the simulator's rule) */
    int full = !sel->fmt.is_signed && sel->fmt.width < 31 && (int64_t)in->n >= ((int64_t)1 << sel->fmt.width);
    if (!full) fprintf(f, "            default: %s__m = %d'b0;\n", nm, mw);
    fprintf(f, "        endcase\n    end\n");
    if (!same) { fprintf(f, "    assign %s = %s__m;\n", nm, nm); return 0; }
    /* quantize the selected value: a temporary wire named like a signal */
    snprintf(pre, sizeof pre, "%s__q", nm);
    int T = mw + !mf.is_signed;
    if (mf.is_signed) fprintf(f, "    wire [%d:0] %s__e = %s__m;\n", T - 1, pre, nm);
    else fprintf(f, "    wire [%d:0] %s__e = {1'b0, %s__m};\n", T - 1, pre, nm);
    char src[320];
    snprintf(src, sizeof src, "%s__e", pre);
    quant(g, pre, src, T, mf.fbits, y->fmt, in->r, in->o, nm);
    return 0;
}

/* Adder, subtractor, multiplier, shift: exact value, then quantize. */
static int emit_arith(vgen *g, const sim_signal *y, const sim_prim_info *in, const sim_signal *clk)
{
    (void)clk;
    FILE *f = g->f;
    const char *nm = N(g, y);
    char ea[300], eb[300], pre[200];
    snprintf(pre, sizeof pre, "%s", nm);
    /* the exact result: src_f fraction bits, operands aligned by sa, sb
     * (sim_prim_describe) */
    int T, src_f = in->src_f, sa = in->sa, sb = in->sb;
    if (y->kind == SIM_KIND_ADD || y->kind == SIM_KIND_SUB) {
        int ta = sw(in->a) + sa, tb = sw(in->b) + sb;
        T = (ta > tb ? ta : tb) + 1;
        ext(ea, sizeof ea, g, in->a, T, sa);
        ext(eb, sizeof eb, g, in->b, T, sb);
        fprintf(f, "    wire [%d:0] %s__a = %s;\n    wire [%d:0] %s__b = %s;\n", T - 1, pre, ea, T - 1, pre, eb);
        fprintf(f, "    wire [%d:0] %s__e = %s__a %c %s__b;\n", T - 1, pre, pre, y->kind == SIM_KIND_ADD ? '+' : '-', pre);
    } else if (y->kind == SIM_KIND_MUL) {
        /* Each operand at its own width as a signed number (an unsigned
         * one zero-extended by a bit), the product at the sum of the two:
         * the exact product fits. Synthesis builds a signed wa x wb
         * multiplier from this; the same product written on operands
         * sign-extended to the full width is a T x T one that it must trim
         * (minutes in ABC for 16 x 16 bits, and more cells). */
        T = sw(in->a) + sw(in->b);
        ext(ea, sizeof ea, g, in->a, sw(in->a), 0);
        ext(eb, sizeof eb, g, in->b, sw(in->b), 0);
        fprintf(f, "    wire [%d:0] %s__e = $signed(%s) * $signed(%s);\n", T - 1, pre, ea, eb);
    } else {   /* shift: x * 2^sh is the raw with fbits - sh fraction bits (scaled up by sa past the point) */
        T = sw(in->a) + sa;
        ext(ea, sizeof ea, g, in->a, T, sa);
        fprintf(f, "    wire [%d:0] %s__e = %s;\n", T - 1, pre, ea);
    }
    char src[220];
    snprintf(src, sizeof src, "%s__e", pre);
    quant(g, pre, src, T, src_f, y->fmt, in->r, in->o, nm);
    return 0;
}

/* One emitter per value of sim_elem.h's vlog column: y's driver, read
 * from its description in, as Verilog. 0, or -1 with g->err set. */
static int emit_const(vgen *g, const sim_signal *y, const sim_prim_info *in, const sim_signal *clk)
{
    char buf[64];
    (void)in; (void)clk;
    lit(buf, sizeof buf, y->fmt.width, y->cur);
    fprintf(g->f, "    assign %s = %s;\n", N(g, y), buf);
    return 0;
}

static int emit_reg(vgen *g, const sim_signal *y, const sim_prim_info *in, const sim_signal *clk)
{
    FILE *f = g->f;
    const char *nm = N(g, y);
    char pre[200];
    if (in->clk != clk) { snprintf(g->err, g->errlen, "register %s has a clock of its own", nm); return -1; }
    char rl[64];
    lit(rl, sizeof rl, y->fmt.width, in->rst_raw);
    if (g->reset == SIM_VRESET_NONE) {
        fprintf(f, "    initial %s = %s;\n", nm, rl);
        if (!in->a) return 0;    /* never loaded: keeps its initial value */
    }
    if (in->a) {
        snprintf(pre, sizeof pre, "%s__d", nm);
        fprintf(f, "    wire [%d:0] %s;\n", y->fmt.width - 1, pre);
        quant_sig(g, pre, in->a, y->fmt, in->r, in->o, pre);
    }
    /* the module's reset first, then the unit's own synchronous one,
     * then the enable */
    fprintf(f, "    always @(posedge clk%s)\n        ", g->reset == SIM_VRESET_ASYNC ? " or posedge rst" : "");
    if (g->reset != SIM_VRESET_NONE) {
        fprintf(f, "if (rst) %s <= %s;\n", nm, rl);
        if (!in->a) return 0;    /* never loaded: keeps its reset value */
        fprintf(f, "        else ");
    }
    if (in->rst) fprintf(f, "if (|%s) %s <= %s;\n        else ", N(g, in->rst), nm, rl);
    if (in->c) fprintf(f, "if (|%s) ", N(g, in->c));
    fprintf(f, "%s <= %s;\n", nm, pre);
    return 0;
}

/* sim_assign into a declared wire (or an input) */
static int emit_copy(vgen *g, const sim_signal *y, const sim_prim_info *in, const sim_signal *clk)
{
    char pre[200];
    const char *nm = N(g, y);
    (void)clk;
    snprintf(pre, sizeof pre, "%s", nm);
    quant_sig(g, pre, in->a, y->fmt, in->r, in->o, nm);
    return 0;
}

static int emit_bk(vgen *g, const sim_signal *y, const sim_prim_info *in, const sim_signal *clk)
{
    char pre[200];
    const char *nm = N(g, y);
    (void)clk;
    snprintf(pre, sizeof pre, "%s__x", nm);
    fprintf(g->f, "    wire [%d:0] %s;\n", y->fmt.width - 1, pre);
    quant_sig(g, pre, in->a, y->fmt, in->r, in->o, pre);
    fprintf(g->f, "    assign %s = (|%s) ? %s : %d'b0;\n", nm, N(g, in->c), pre, y->fmt.width);
    return 0;
}

static int emit_none(vgen *g, const sim_signal *y, const sim_prim_info *in, const sim_signal *clk)
{
    (void)in; (void)clk;
    snprintf(g->err, g->errlen, "signal %s: an element the export does not know", N(g, y));
    return -1;
}

static int emit_sig(vgen *g, const sim_signal *y, const sim_signal *clk, int is_input_port)
{
    FILE *f = g->f;
    const char *nm = N(g, y);
    char buf[64];
    if (is_input_port) return 0;
    sim_prim_info in;
    if (sim_prim_describe(y, &in)) {
        snprintf(g->err, g->errlen, "signal %s is driven by nothing the export knows (an input that is not a port, or a process of its own)", nm);
        return -1;
    }
    const sim_signal *ops[3] = { in.a, in.b, in.c };
    for (int i = 0; i < 3; i++)
        if (ops[i] && !g->name[ops[i]->index]) {
            snprintf(g->err, g->errlen, "signal %s reads %s, outside the unit", nm, ops[i]->name);
            return -1;
        }
    for (int i = 0; i < in.n; i++)
        if (!g->name[in.in[i]->index]) {
            snprintf(g->err, g->errlen, "signal %s reads %s, outside the unit", nm, in.in[i]->name);
            return -1;
        }
    fprintf(f, "    // %s: %s\n", nm, sim_fmt_str(y->fmt, buf));
    /* the kind's emitter: sim_elem.h's vlog column */
#define EMIT_OF(K, name, role, eval, vlog, ...) [SIM_KIND_##K] = emit_##vlog,
    static int (*const emit_kind[SIM_KIND__COUNT])(vgen *, const sim_signal *, const sim_prim_info *,
                                                 const sim_signal *) = { SIM_ELEM_LIST(EMIT_OF) };
#undef EMIT_OF
    if (y->kind >= SIM_KIND__COUNT) return emit_none(g, y, &in, clk);
    return emit_kind[y->kind](g, y, &in, clk);
}

int sim_verilog_module(FILE *f, const sim_ctx *c, const sim_scope *sc, const char *module,
                       const sim_signal *clk, sim_vreset reset, const sim_vport *ports, int nports,
                       char *err, size_t errlen)
{
    vgen g = { f, c, sc, NULL, sim_signal_count(c), reset, err, errlen };
    g.name = calloc(g.nsig ? g.nsig : 1, sizeof *g.name);
    signed char *port_of = calloc(g.nsig ? g.nsig : 1, 1);   /* 1 input port, 2 output port */
    int rc = -1;
    char *extra_assign[64];
    int nextra = 0;
    if (!g.name || !port_of) { snprintf(err, errlen, "out of memory"); goto done; }
    /* Port names first; a signal that is two ports is named after the first. */
    for (int i = 0; i < nports; i++) {
        uint32_t k = ports[i].sig->index;
        if (!g.name[k]) {
            g.name[k] = strdup(ports[i].name);
            port_of[k] = ports[i].is_output ? 2 : 1;
        } else if (ports[i].is_output && nextra < 64) {
            char line[200];
            snprintf(line, sizeof line, "    assign %s = %s;\n", ports[i].name, g.name[k]);
            extra_assign[nextra++] = strdup(line);
        }
    }
    for (uint32_t i = 0; i < g.nsig; i++) {
        sim_signal *s = sim_signal_at(c, i);
        if (g.name[i] || s == clk || !in_scope(s, sc)) continue;
        char nm[200], cand[220];
        flat_name(s, sc, nm, sizeof nm);
        snprintf(cand, sizeof cand, "%s%s", nm, is_keyword(nm) ? "_s" : "");
        for (int k = 2; name_taken(&g, cand); k++) snprintf(cand, sizeof cand, "%s_%d", nm, k);
        for (int j = 0; j < nports; j++) if (!strcmp(cand, ports[j].name)) snprintf(cand, sizeof cand, "%s_i", nm);
        g.name[i] = strdup(cand);
    }

    fprintf(f, "module %s (\n    input  wire clk", module);
    if (reset != SIM_VRESET_NONE) fprintf(f, ",\n    input  wire rst");
    for (int i = 0; i < nports; i++) {
        const sim_signal *s = ports[i].sig;
        int is_reg = ports[i].is_output && s->kind == SIM_KIND_REG && !strcmp(g.name[s->index], ports[i].name);
        fprintf(f, ",\n    %s %s [%d:0] %s", ports[i].is_output ? "output" : "input ",
                is_reg ? "reg " : "wire", ports[i].sig->fmt.width - 1, ports[i].name);
    }
    fprintf(f, "\n);\n");
    /* declarations, then the elements (in creation order) */
    for (uint32_t i = 0; i < g.nsig; i++) {
        sim_signal *s = sim_signal_at(c, i);
        if (!g.name[i] || port_of[i]) continue;
        char fb[SIM_FMT_STRLEN];
        fprintf(f, "    %s [%d:0] %s;   // %s\n", s->kind == SIM_KIND_REG ? "reg " : "wire", s->fmt.width - 1,
                g.name[i], sim_fmt_str(s->fmt, fb));
    }
    for (int i = 0; i < nports; i++) {
        const sim_signal *s = ports[i].sig;
        if (ports[i].is_output) continue;
        if (s->driver) { snprintf(err, errlen, "input port %s is driven inside the unit", ports[i].name); goto done; }
    }
    for (uint32_t i = 0; i < g.nsig; i++) {
        sim_signal *s = sim_signal_at(c, i);
        if (!g.name[i]) continue;
        if (port_of[i] == 2 && s->kind == SIM_KIND_INPUT && !s->driver) {
            snprintf(err, errlen, "output port %s is an undriven input", g.name[i]);
            goto done;
        }
        if (emit_sig(&g, s, clk, port_of[i] == 1)) goto done;
    }
    for (int i = 0; i < nextra; i++) fputs(extra_assign[i], f);
    fprintf(f, "endmodule\n");
    rc = 0;
done:
    for (int i = 0; i < nextra; i++) free(extra_assign[i]);
    if (g.name) for (uint32_t i = 0; i < g.nsig; i++) free(g.name[i]);
    free(g.name);
    free(port_of);
    return rc;
}
