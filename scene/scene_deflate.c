/* scene_deflate.c - a DEFLATE compressor (RFC 1951) for the PNG encoder.
 *
 * LZ77: a 32K window, a hash of the next three bytes into chains of earlier
 * positions (head[] per hash, prev[] per window slot), a bounded walk down
 * the chain, and lazy matching: a match shorter than `lazy` is kept only if
 * the next position does not start a longer one. Matches are 3..258 bytes
 * at distances up to WMAX.
 *
 * Blocks: the symbols of up to BLK_SYMS tokens make one block, which is
 * written the cheapest of three ways, counted exactly in bits beforehand:
 * dynamic Huffman codes built from the block's frequencies (lengths limited
 * to 15 bits, the code-length code to 7), the fixed codes, or stored bytes
 * (incompressible data then grows by 5 bytes per 64K block only).
 *
 * Every choice depends on the input alone (ties broken by symbol number),
 * so the same input gives the same bytes; the tables live in one heap
 * block per call, so threads may compress at once.
 */
#include "scene/scene.h"
#include <stdlib.h>
#include <string.h>

#define WSIZE    32768u
#define WMASK    (WSIZE - 1)
#define WMAX     (WSIZE - 262)     /* as zlib: a safe distance below the window */
#define HBITS    15
#define MINM     3
#define MAXM     258
#define BLK_SYMS 32768u            /* tokens per block: long enough to pay for a header */

/* length codes 257..285: base lengths and extra bits */
static const uint16_t len_base[29] = { 3, 4, 5, 6, 7, 8, 9, 10, 11, 13, 15, 17, 19, 23, 27, 31,
                                       35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258 };
static const uint8_t len_xb[29] = { 0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2,
                                    3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0 };
static const uint16_t dist_base[30] = { 1, 2, 3, 4, 5, 7, 9, 13, 17, 25, 33, 49, 65, 97, 129, 193,
                                        257, 385, 513, 769, 1025, 1537, 2049, 3073, 4097, 6145,
                                        8193, 12289, 16385, 24577 };
static const uint8_t dist_xb[30] = { 0, 0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 5, 5, 6, 6,
                                     7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12, 13, 13 };
/* order of the code-length code's lengths in the header */
static const uint8_t cl_order[19] = { 16, 17, 18, 0, 8, 7, 9, 6, 10, 5, 11, 4, 12, 3, 13, 2, 14, 1, 15 };

/* ------------------------------------------------------------ bit output */

typedef struct zout {
    uint8_t *b;
    size_t   n, cap;
    uint64_t acc;                 /* pending bits, LSB first */
    int      nacc;
    int      oom;
} zout;

static void zo_reserve(zout *o, size_t more)
{
    if (o->oom || o->n + more <= o->cap) return;
    size_t c = o->cap ? o->cap : 4096;
    while (c < o->n + more) c *= 2;
    uint8_t *nb = realloc(o->b, c);
    if (!nb) { o->oom = 1; return; }
    o->b = nb;
    o->cap = c;
}

/* Append n <= 32 bits, least significant first (deflate's bit order). */
static void zo_bits(zout *o, uint32_t v, int n)
{
    o->acc |= (uint64_t)v << o->nacc;
    o->nacc += n;
    if (o->nacc >= 32) {
        zo_reserve(o, 4);
        if (!o->oom) for (int k = 0; k < 4; k++) o->b[o->n++] = (uint8_t)(o->acc >> (8 * k));
        o->acc >>= 32;
        o->nacc -= 32;
    }
}

static void zo_align(zout *o)
{
    zo_reserve(o, 8);
    while (o->nacc > 0) {
        if (!o->oom) o->b[o->n++] = (uint8_t)o->acc;
        o->acc >>= 8;
        o->nacc = o->nacc > 8 ? o->nacc - 8 : 0;
    }
    o->acc = 0;
}

/* Huffman codes are sent most significant bit first: reverse them once. */
static uint32_t rev(uint32_t c, int n)
{
    uint32_t r = 0;
    for (int k = 0; k < n; k++, c >>= 1) r = (r << 1) | (c & 1);
    return r;
}

/* ------------------------------------------------------ Huffman lengths */

/* Code lengths for n symbols of frequencies f, none longer than limit:
 * a Huffman tree by the two-queue method over leaves sorted by (frequency,
 * symbol), then, if it is too deep, the lengths redistributed (the deepest
 * codes cut to limit and the Kraft sum restored by lengthening the codes
 * just above, as zlib's gen_bitlen and miniz do). At least two symbols get
 * a code, so every code is complete. */
static void huff_lengths(const uint32_t *f_in, int n, int limit, uint8_t *len)
{
    uint32_t f[288];
    int sym[288], nz = 0;
    memcpy(f, f_in, (size_t)n * sizeof f[0]);
    for (int i = 0; i < n && nz < 2; i++)
        if (f[i]) nz++;
    for (int i = 0; i < n && nz < 2; i++)
        if (!f[i]) { f[i] = 1; nz++; }
    nz = 0;
    for (int i = 0; i < n; i++) {
        len[i] = 0;
        if (f[i]) sym[nz++] = i;
    }
    /* insertion sort by (frequency, symbol): stable and small (n <= 288) */
    for (int i = 1; i < nz; i++) {
        int s = sym[i], j = i;
        while (j > 0 && f[sym[j - 1]] > f[s]) { sym[j] = sym[j - 1]; j--; }
        sym[j] = s;
    }
    /* nodes 0..nz-1 leaves (in sorted order), nz.. internal, made in order
     * of non-decreasing weight, so two queues replace a heap */
    uint64_t w[2 * 288];
    int parent[2 * 288];
    for (int i = 0; i < nz; i++) w[i] = f[sym[i]];
    int li = 0, ii = nz, nn = nz;
    for (int k = 0; k < nz - 1; k++) {
        int pick[2];
        for (int t = 0; t < 2; t++)
            pick[t] = (li < nz && (ii >= nn || w[li] <= w[ii])) ? li++ : ii++;
        w[nn] = w[pick[0]] + w[pick[1]];
        parent[pick[0]] = parent[pick[1]] = nn;
        nn++;
    }
    /* depths: parents come after children, so walk from the root down */
    int depth[2 * 288];
    depth[nn - 1] = 0;
    for (int i = nn - 2; i >= 0; i--) depth[i] = depth[parent[i]] + 1;
    int count[64] = { 0 }, over = 0;
    for (int i = 0; i < nz; i++) {
        int d = depth[i];
        if (d > limit) { d = limit; over = 1; }
        count[d]++;
    }
    if (over) {
        /* Kraft sum in units of 2^-limit; cut codes made it exceed 1 */
        uint64_t total = 0;
        for (int d = 1; d <= limit; d++) total += (uint64_t)count[d] << (limit - d);
        while (total > (1ull << limit)) {
            count[limit]--;
            for (int d = limit - 1; d > 0; d--)
                if (count[d]) { count[d]--; count[d + 1] += 2; break; }
            total--;
        }
    }
    /* longest codes to the rarest symbols: leaves are sorted by frequency */
    int i = 0;
    for (int d = limit; d >= 1; d--)
        for (int c = 0; c < count[d]; c++) len[sym[i++]] = (uint8_t)d;
}

/* Canonical codes (RFC 1951 3.2.2), bit-reversed for sending. */
static void huff_codes(const uint8_t *len, int n, uint16_t *code)
{
    int count[16] = { 0 };
    uint32_t next[16];
    for (int i = 0; i < n; i++) count[len[i]]++;
    count[0] = 0;
    uint32_t c = 0;
    for (int b = 1; b < 16; b++) { c = (c + (uint32_t)count[b - 1]) << 1; next[b] = c; }
    for (int i = 0; i < n; i++)
        code[i] = len[i] ? (uint16_t)rev(next[len[i]]++, len[i]) : 0;
}

/* --------------------------------------------------------------- blocks */

/* A token: a literal (dist 0, lit = byte) or a match (len 3..258, dist). */
typedef struct ztok { uint16_t len, dist; } ztok;

/* Length 3..258 -> code 0..28 and distance 1..32768 -> code 0..29 by the
 * tables' structure: past the first codes, each power of two of (length
 * - 3) holds four codes, each of (distance - 1) two. */
static int len_code(int l)
{
    unsigned v = (unsigned)l - 3;
    if (l == 258) return 28;
    if (v < 8) return (int)v;
    int k = 31 - __builtin_clz(v);
    return 4 * (k - 1) + (int)((v >> (k - 2)) & 3);
}

static int dist_code(int d)
{
    unsigned v = (unsigned)d - 1;
    if (v < 4) return (int)v;
    int k = 31 - __builtin_clz(v);
    return 2 * k + (int)((v >> (k - 1)) & 1);
}

/* The run-length coded code lengths of a dynamic header: symbols 0..18
 * with their extra values. Returns the number of items. */
static int cl_encode(const uint8_t *lens, int n, uint8_t *sym, uint8_t *xv)
{
    int m = 0;
    for (int i = 0; i < n;) {
        int l = lens[i], r = 1;
        while (i + r < n && lens[i + r] == l) r++;
        if (l == 0 && r >= 3) {
            int k = r > 138 ? 138 : r;
            if (k >= 11) { sym[m] = 18; xv[m++] = (uint8_t)(k - 11); }
            else { sym[m] = 17; xv[m++] = (uint8_t)(k - 3); }
            i += k;
        } else if (l != 0 && r >= 4) {
            sym[m] = (uint8_t)l; xv[m++] = 0;          /* once, then repeats of 3..6 */
            i++;
            r--;
            while (r >= 3) {
                int k = r > 6 ? 6 : r;
                sym[m] = 16; xv[m++] = (uint8_t)(k - 3);
                i += k;
                r -= k;
            }
        } else {
            sym[m] = (uint8_t)l; xv[m++] = 0;
            i++;
        }
    }
    return m;
}

static const uint8_t cl_xb[19] = { [16] = 2, [17] = 3, [18] = 7 };

/* Write tokens t[0..nt) (covering input bytes in[0..nb)) as one block. */
static void write_block(zout *o, const ztok *t, size_t nt, const uint8_t *in, size_t nb, int final)
{
    uint32_t fl[286] = { 0 }, fd[30] = { 0 };
    uint64_t xbits = 0;             /* extra bits of lengths and distances */
    for (size_t i = 0; i < nt; i++) {
        if (!t[i].dist) { fl[t[i].len]++; continue; }
        int lc = len_code(t[i].len), dc = dist_code(t[i].dist);
        fl[257 + lc]++;
        fd[dc]++;
        xbits += len_xb[lc] + dist_xb[dc];
    }
    fl[256] = 1;

    /* dynamic: lengths, the header's code-length code */
    uint8_t ll[286], dl[30];
    huff_lengths(fl, 286, 15, ll);
    huff_lengths(fd, 30, 15, dl);
    int hlit = 286, hdist = 30;
    while (hlit > 257 && !ll[hlit - 1]) hlit--;
    while (hdist > 1 && !dl[hdist - 1]) hdist--;
    uint8_t all[316], cs[316], cx[316];
    memcpy(all, ll, (size_t)hlit);
    memcpy(all + hlit, dl, (size_t)hdist);
    int ncs = cl_encode(all, hlit + hdist, cs, cx);
    uint32_t fc[19] = { 0 };
    for (int i = 0; i < ncs; i++) fc[cs[i]]++;
    uint8_t cl[19];
    huff_lengths(fc, 19, 7, cl);
    int hclen = 19;
    while (hclen > 4 && !cl[cl_order[hclen - 1]]) hclen--;
    uint64_t dyn = 3 + 5 + 5 + 4 + 3 * (uint64_t)hclen + xbits;
    for (int i = 0; i < ncs; i++) dyn += cl[cs[i]] + cl_xb[cs[i]];
    for (int i = 0; i < 286; i++) dyn += (uint64_t)fl[i] * ll[i];
    for (int i = 0; i < 30; i++) dyn += (uint64_t)fd[i] * dl[i];

    /* fixed codes (RFC 1951 3.2.6) */
    uint8_t fll[288], fdl[30];
    for (int i = 0; i < 288; i++) fll[i] = i < 144 ? 8 : i < 256 ? 9 : i < 280 ? 7 : 8;
    memset(fdl, 5, sizeof fdl);
    uint64_t fix = 3 + xbits;
    for (int i = 0; i < 286; i++) fix += (uint64_t)fl[i] * fll[i];
    for (int i = 0; i < 30; i++) fix += (uint64_t)fd[i] * 5;

    /* stored: a header and LEN/NLEN per 65535 bytes, after byte alignment */
    size_t nst = nb / 65535 + (nb % 65535 != 0 || nb == 0);
    uint64_t sto = (uint64_t)nst * (3 + 7 + 32) + 8 * (uint64_t)nb;

    if (sto <= dyn && sto <= fix) {
        for (size_t k = 0, done = 0; k < nst; k++) {
            size_t m = nb - done < 65535 ? nb - done : 65535;
            zo_bits(o, (uint32_t)(final && k + 1 == nst), 3);   /* BTYPE 00 */
            zo_align(o);
            zo_reserve(o, 4 + m);
            if (o->oom) return;
            o->b[o->n++] = (uint8_t)m;
            o->b[o->n++] = (uint8_t)(m >> 8);
            o->b[o->n++] = (uint8_t)~m;
            o->b[o->n++] = (uint8_t)(~m >> 8);
            memcpy(o->b + o->n, in + done, m);
            o->n += m;
            done += m;
        }
        return;
    }
    const uint8_t *L, *D;
    if (dyn < fix) {
        zo_bits(o, (uint32_t)final | 2u << 1, 3);               /* BTYPE 10 */
        zo_bits(o, (uint32_t)(hlit - 257), 5);
        zo_bits(o, (uint32_t)(hdist - 1), 5);
        zo_bits(o, (uint32_t)(hclen - 4), 4);
        for (int i = 0; i < hclen; i++) zo_bits(o, cl[cl_order[i]], 3);
        uint16_t cc[19];
        huff_codes(cl, 19, cc);
        for (int i = 0; i < ncs; i++) {
            zo_bits(o, cc[cs[i]], cl[cs[i]]);
            if (cl_xb[cs[i]]) zo_bits(o, cx[i], cl_xb[cs[i]]);
        }
        L = ll;
        D = dl;
    } else {
        zo_bits(o, (uint32_t)final | 1u << 1, 3);               /* BTYPE 01 */
        L = fll;
        D = fdl;
    }
    uint16_t lcode[288], dcode[30];
    huff_codes(L, L == fll ? 288 : 286, lcode);
    huff_codes(D, 30, dcode);
    for (size_t i = 0; i < nt; i++) {
        if (!t[i].dist) { zo_bits(o, lcode[t[i].len], L[t[i].len]); continue; }
        int lc = len_code(t[i].len), dc = dist_code(t[i].dist);
        zo_bits(o, lcode[257 + lc], L[257 + lc]);
        if (len_xb[lc]) zo_bits(o, (uint32_t)(t[i].len - len_base[lc]), len_xb[lc]);
        zo_bits(o, dcode[dc], D[dc]);
        if (dist_xb[dc]) zo_bits(o, (uint32_t)(t[i].dist - dist_base[dc]), dist_xb[dc]);
    }
    zo_bits(o, lcode[256], L[256]);
}

/* ---------------------------------------------------------------- LZ77 */

typedef struct lz {
    const uint8_t *in;
    size_t n;
    uint32_t head[1u << HBITS];    /* position + 1 of the latest string per hash, 0 = none */
    uint32_t prev[WSIZE];          /* position + 1 of the previous string of the same hash */
    size_t ins;                    /* positions below ins are in the chains */
    int chain, nice;
} lz;

static uint32_t hash3(const uint8_t *p)
{
    uint32_t v = (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16;
    return (v * 2654435761u) >> (32 - HBITS);
}

static void lz_insert_upto(lz *z, size_t p)
{
    for (; z->ins < p; z->ins++) {
        if (z->ins + MINM > z->n) continue;
        uint32_t h = hash3(z->in + z->ins);
        z->prev[z->ins & WMASK] = z->head[h];
        z->head[h] = (uint32_t)z->ins + 1;
    }
}

/* The longest match at p (the first found among equals: the nearest). */
static int lz_find(lz *z, size_t p, int *dist)
{
    lz_insert_upto(z, p);
    size_t avail = z->n - p;
    if (avail < MINM) return 0;
    int maxl = avail < MAXM ? (int)avail : MAXM, best = MINM - 1;
    const uint8_t *s = z->in + p;
    uint32_t c = z->head[hash3(s)];
    for (int k = 0; k < z->chain && c; k++) {
        size_t q = c - 1;
        if (q >= p || p - q > WMAX) break;
        const uint8_t *t = z->in + q;
        if (t[best] == s[best] && t[0] == s[0] && t[1] == s[1]) {
            int l = 2;
            while (l < maxl && t[l] == s[l]) l++;
            if (l > best) {
                best = l;
                *dist = (int)(p - q);
                if (l >= z->nice || l == maxl) break;
            }
        }
        uint32_t nc = z->prev[q & WMASK];
        if (nc >= c) break;            /* a slot reused by a newer string: end of chain */
        c = nc;
    }
    return best >= MINM ? best : 0;
}

int scn_deflate(const uint8_t *in, size_t n, int level, uint8_t **out, size_t *outlen)
{
    *out = NULL;
    *outlen = 0;
    if ((!in && n) || n >= UINT32_MAX) return -1;     /* chains hold positions + 1 in 32 bits */
    zout o = { 0 };
    lz *z = calloc(1, sizeof *z);
    ztok *t = malloc(BLK_SYMS * sizeof *t);
    if (!z || !t) { free(z); free(t); return -1; }
    z->in = in;
    z->n = n;
    /* level 1: short chains, lazy below 8; level 2 and up: longer, lazy below 32 */
    z->chain = level >= 2 ? 128 : 8;
    z->nice = level >= 2 ? 128 : 32;
    int lazy = level >= 2 ? 32 : 8;
    size_t nt = 0, p = 0, bstart = 0;
    int cl = 0, cd = 0, cached = 0;
    while (p < n) {
        int l = 0, d = 0;
        if (level > 0) {
            if (cached) { l = cl; d = cd; cached = 0; }
            else l = lz_find(z, p, &d);
            if (l && l < lazy && p + 1 < n) {
                int d2 = 0, l2 = lz_find(z, p + 1, &d2);
                if (l2 > l) { cl = l2; cd = d2; cached = 1; l = 0; }
            }
        }
        if (l) {
            t[nt].len = (uint16_t)l;
            t[nt].dist = (uint16_t)d;
            /* Fast level: the inside of a long match (a run of background)
             * is not hashed, as zlib's fast levels do; its last strings are. */
            if (level == 1 && l > z->nice && !cached && z->ins < p + (size_t)l - 3) z->ins = p + (size_t)l - 3;
            p += (size_t)l;
        } else {
            t[nt].len = in[p];
            t[nt].dist = 0;
            p++;
        }
        /* a full block ends here (a cached match starts at p < n, so the
         * block is final only when the input is done) */
        if (++nt == BLK_SYMS) {
            write_block(&o, t, nt, in + bstart, p - bstart, p == n);
            nt = 0;
            bstart = p;
        }
    }
    /* the rest, or an empty final block for empty input */
    if (nt || n == 0) write_block(&o, t, nt, in + bstart, n - bstart, 1);
    zo_align(&o);
    free(z);
    free(t);
    if (o.oom) { free(o.b); return -1; }
    *out = o.b;
    *outlen = o.n;
    return 0;
}
