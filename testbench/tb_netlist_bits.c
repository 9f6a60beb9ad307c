/* tb_netlist_bits.c - a logic element that is wiring, as text: its output
 * as a concatenation of its inputs' bits and constant bits (tb_netlist_int.h,
 * docs/netlist.md, "bits="). The widest logic elements of the units are
 * wiring of this kind (a remainder shifted left with the next bit in, a
 * sign bit inverted), too wide for a truth table but not for this. */
#include "testbench/tb_netlist_int.h"
#include <string.h>

static uint64_t mask_of(int w) { return w >= 64 ? UINT64_MAX : (((uint64_t)1 << w) - 1); }

static const char *num(const char *p, int *v)
{
    if (*p < '0' || *p > '9') return NULL;
    long n = 0;
    while (*p >= '0' && *p <= '9' && n < 1000) n = n * 10 + (*p++ - '0');
    *v = (int)n;
    return p;
}

/* One item at p: [~]%K, [~]%K[B], [~]%K[H:L], or W'bBITS / W'hHEX. */
static const char *item(const char *p, int nin, const int *w, nl_bits_item *it)
{
    memset(it, 0, sizeof *it);
    if (*p == '~') { it->inv = 1; p++; }
    int k, hi, lo;
    if (*p == '%') {
        if (!(p = num(p + 1, &k)) || k >= nin) return NULL;
        it->in = (int8_t)k;
        hi = w[k] - 1;
        lo = 0;
        if (*p == '[') {
            if (!(p = num(p + 1, &hi))) return NULL;
            lo = hi;
            if (*p == ':' && !(p = num(p + 1, &lo))) return NULL;
            if (*p++ != ']') return NULL;
        }
        if (hi < lo || hi >= w[k]) return NULL;
        it->hi = (uint8_t)hi;
        it->lo = (uint8_t)lo;
        return p;
    }
    int cw;
    if (!(p = num(p, &cw)) || cw < 1 || cw > 64 || *p++ != '\'') return NULL;
    int base = *p == 'b' ? 2 : *p == 'h' ? 16 : 0, digits = 0;
    if (!base) return NULL;
    uint64_t v = 0;
    for (p++;; p++, digits++) {
        int d = *p >= '0' && *p <= '9' ? *p - '0' : *p >= 'a' && *p <= 'f' ? *p - 'a' + 10 : -1;
        if (d < 0 || d >= base) break;
        if (v >> (base == 2 ? 63 : 60)) return NULL;
        v = v * (uint64_t)base + (uint64_t)d;
    }
    if (!digits || (v & ~mask_of(cw))) return NULL;
    it->in = -1;
    it->hi = (uint8_t)(cw - 1);
    it->k = v;
    return p;
}

int nl_bits_parse(const char *text, int nin, const int *in_width, nl_bits *out)
{
    memset(out, 0, sizeof *out);
    const char *p = text;
    int braces = *p == '{';
    if (braces) p++;
    int total = 0;
    for (;;) {
        if (out->n == NL_BITS_MAX) return -1;
        nl_bits_item *it = &out->item[out->n++];
        if (!(p = item(p, nin, in_width, it))) return -1;
        total += it->hi - it->lo + 1;
        if (!braces || *p != ',') break;
        p++;
    }
    if (braces && *p++ != '}') return -1;
    if (*p || total > 64) return -1;
    return 0;
}

int64_t nl_bits_fn(const int64_t *in, void *user)
{
    const nl_bits *b = user;
    uint64_t v = 0;
    for (int i = 0; i < b->n; i++) {
        const nl_bits_item *it = &b->item[i];
        int w = it->hi - it->lo + 1;
        uint64_t x = it->in < 0 ? it->k : ((uint64_t)in[it->in] >> it->lo) & mask_of(w);
        if (it->inv) x = ~x & mask_of(w);
        v = (w >= 64 ? 0 : v << w) | x;
    }
    return (int64_t)v;
}

/* The text's form: "{A,B,...}" or one item, no blanks. */
void nl_bits_put(FILE *f, const nl_bits *b)
{
    if (b->n > 1) fputc('{', f);
    for (int i = 0; i < b->n; i++) {
        const nl_bits_item *it = &b->item[i];
        if (i) fputc(',', f);
        if (it->inv) fputc('~', f);
        if (it->in < 0) fprintf(f, "%d'h%llx", it->hi + 1, (unsigned long long)it->k);
        else if (it->hi == it->lo) fprintf(f, "%%%d[%d]", it->in, it->hi);
        else fprintf(f, "%%%d[%d:%d]", it->in, it->hi, it->lo);
    }
    if (b->n > 1) fputc('}', f);
}
