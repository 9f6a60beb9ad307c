/* test_png.c - the PNG encoder and the DEFLATE compressor against an
 * independent decoder written here from the specifications: chunk walk,
 * CRC-32 recomputed bit by bit, the zlib header, an inflate after RFC 1951
 * (stored, fixed and dynamic blocks; canonical codes decoded by counting
 * codes per length, rejecting over-subscribed and incomplete codes), the
 * Adler-32, and PNG's five filters undone; plus pngcheck and python3's
 * zlib as outside references when they are installed; and the colour maps.
 */
#include "tests/tst.h"
#include "scene/scene.h"
#include <errno.h>
#include <stdint.h>

static char tdir[512];

static uint32_t be32(const uint8_t *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

/* CRC-32 bit by bit, no table: the definition (ISO 3309, reflected). */
static uint32_t crc_bitwise(const uint8_t *p, size_t n)
{
    uint32_t c = 0xFFFFFFFFu;
    for (size_t i = 0; i < n; i++) {
        c ^= p[i];
        for (int k = 0; k < 8; k++) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
    }
    return ~c;
}

/* Adler-32 the long way (sums modulo 65521 at every step). */
static uint32_t adler_slow(const uint8_t *p, size_t n)
{
    uint64_t a = 1, b = 0;
    for (size_t i = 0; i < n; i++) { a = (a + p[i]) % 65521; b = (b + a) % 65521; }
    return (uint32_t)(b << 16 | a);
}

/* ------------------------------------------------------------ inflate */

/* RFC 1951 read literally: bits LSB first, Huffman codes MSB first, codes
 * canonical from the lengths alone. Written for clarity, not speed. */
typedef struct inf {
    const uint8_t *in;
    size_t n, pos;                 /* byte position */
    int bit;                       /* next bit in in[pos] */
    uint8_t *out;
    size_t on, ocap;
    int nblk[3];                   /* blocks of each type: stored, fixed, dynamic */
    int maxlen;                    /* longest code length seen in a dynamic block */
    const char *err;
} inf;

static int getbit(inf *s)
{
    if (s->pos >= s->n) { s->err = "input ends"; return 0; }
    int b = (s->in[s->pos] >> s->bit) & 1;
    if (++s->bit == 8) { s->bit = 0; s->pos++; }
    return b;
}

static unsigned getbits(inf *s, int k)
{
    unsigned v = 0;
    for (int i = 0; i < k; i++) v |= (unsigned)getbit(s) << i;
    return v;
}

static void put(inf *s, uint8_t c)
{
    if (s->on == s->ocap) {
        s->ocap = s->ocap ? 2 * s->ocap : 1024;
        s->out = realloc(s->out, s->ocap);
    }
    s->out[s->on++] = c;
}

/* A code: count[L] codes of length L, symbols in canonical order. */
typedef struct code { int count[16]; int sym[320]; } code;

/* Build from lengths; -1 if over-subscribed, or incomplete while more than
 * one symbol has a code (RFC 1951 allows one code of one bit alone). */
static int build(code *c, const uint8_t *len, int n)
{
    memset(c->count, 0, sizeof c->count);
    for (int i = 0; i < n; i++) c->count[len[i]]++;
    int used = n - c->count[0];
    long left = 1;
    for (int L = 1; L < 16; L++) {
        left = 2 * left - c->count[L];
        if (left < 0) return -1;
    }
    if (left > 0 && used > 1) return -1;
    int offs[16];
    offs[1] = 0;
    for (int L = 1; L < 15; L++) offs[L + 1] = offs[L] + c->count[L];
    for (int i = 0; i < n; i++)
        if (len[i]) c->sym[offs[len[i]]++] = i;
    return 0;
}

/* Read one symbol: the first code of length L is first, codes of length L
 * are first .. first + count[L] - 1. */
static int decode_sym(inf *s, const code *c)
{
    int v = 0, first = 0, index = 0;
    for (int L = 1; L < 16; L++) {
        v |= getbit(s);
        if (v - first < c->count[L]) return c->sym[index + v - first];
        index += c->count[L];
        first = (first + c->count[L]) << 1;
        v <<= 1;
    }
    s->err = "bad code";
    return -1;
}

static const int lbase[29] = { 3, 4, 5, 6, 7, 8, 9, 10, 11, 13, 15, 17, 19, 23, 27, 31, 35, 43, 51, 59,
                               67, 83, 99, 115, 131, 163, 195, 227, 258 };
static const int lext[29] = { 0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3, 4, 4, 4, 4,
                              5, 5, 5, 5, 0 };
static const int dbase[30] = { 1, 2, 3, 4, 5, 7, 9, 13, 17, 25, 33, 49, 65, 97, 129, 193, 257, 385,
                               513, 769, 1025, 1537, 2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577 };
static const int dext[30] = { 0, 0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 5, 5, 6, 6, 7, 7, 8, 8, 9, 9,
                              10, 10, 11, 11, 12, 12, 13, 13 };

static int codes(inf *s, const code *lc, const code *dc)
{
    for (;;) {
        int sym = decode_sym(s, lc);
        if (s->err) return -1;
        if (sym < 256) { put(s, (uint8_t)sym); continue; }
        if (sym == 256) return 0;
        sym -= 257;
        if (sym >= 29) { s->err = "length code 286/287"; return -1; }
        int len = lbase[sym] + (int)getbits(s, lext[sym]);
        int ds = decode_sym(s, dc);
        if (s->err) return -1;
        if (ds >= 30) { s->err = "distance code 30/31"; return -1; }
        size_t dist = (size_t)dbase[ds] + getbits(s, dext[ds]);
        if (dist > s->on || dist > 32768) { s->err = "distance too far"; return -1; }
        for (int k = 0; k < len; k++) put(s, s->out[s->on - dist]);
    }
}

/* Inflate a raw deflate stream; s->pos is left after the last byte used. */
static int inflate_raw(inf *s)
{
    int last;
    do {
        last = getbit(s);
        int type = (int)getbits(s, 2);
        if (s->err) return -1;
        if (type == 0) {
            if (s->bit) { s->bit = 0; s->pos++; }
            if (s->pos + 4 > s->n) { s->err = "stored header"; return -1; }
            unsigned len = s->in[s->pos] | s->in[s->pos + 1] << 8;
            unsigned nlen = s->in[s->pos + 2] | s->in[s->pos + 3] << 8;
            if ((len ^ 0xFFFFu) != nlen) { s->err = "LEN/NLEN"; return -1; }
            s->pos += 4;
            if (s->pos + len > s->n) { s->err = "stored data"; return -1; }
            for (unsigned k = 0; k < len; k++) put(s, s->in[s->pos++]);
            s->nblk[0]++;
        } else if (type == 1) {
            uint8_t l[288];
            for (int i = 0; i < 288; i++) l[i] = i < 144 ? 8 : i < 256 ? 9 : i < 280 ? 7 : 8;
            code lc, dc;
            build(&lc, l, 288);
            memset(l, 5, 32);              /* 32 codes of 5 bits; 30 and 31 are invalid */
            build(&dc, l, 32);
            if (codes(s, &lc, &dc)) return -1;
            s->nblk[1]++;
        } else if (type == 2) {
            int nlen = (int)getbits(s, 5) + 257, ndist = (int)getbits(s, 5) + 1, ncode = (int)getbits(s, 4) + 4;
            static const int ord[19] = { 16, 17, 18, 0, 8, 7, 9, 6, 10, 5, 11, 4, 12, 3, 13, 2, 14, 1, 15 };
            if (nlen > 286 || ndist > 30) { s->err = "too many codes"; return -1; }
            uint8_t l[320] = { 0 };
            for (int i = 0; i < ncode; i++) l[ord[i]] = (uint8_t)getbits(s, 3);
            code lc, dc;
            if (build(&lc, l, 19)) { s->err = "code-length code"; return -1; }
            memset(l, 0, sizeof l);
            for (int i = 0; i < nlen + ndist;) {
                int sym = decode_sym(s, &lc), rep, val = 0;
                if (s->err) return -1;
                if (sym < 16) { l[i++] = (uint8_t)sym; continue; }
                if (sym == 16) {
                    if (!i) { s->err = "repeat with no previous length"; return -1; }
                    val = l[i - 1];
                    rep = 3 + (int)getbits(s, 2);
                } else if (sym == 17) rep = 3 + (int)getbits(s, 3);
                else rep = 11 + (int)getbits(s, 7);
                if (i + rep > nlen + ndist) { s->err = "lengths overrun"; return -1; }
                while (rep--) l[i++] = (uint8_t)val;
            }
            if (!l[256]) { s->err = "no end-of-block code"; return -1; }
            for (int i = 0; i < nlen + ndist; i++)
                if (l[i] > s->maxlen) s->maxlen = l[i];
            if (build(&lc, l, nlen) || build(&dc, l + nlen, ndist)) { s->err = "bad lengths"; return -1; }
            if (codes(s, &lc, &dc)) return -1;
            s->nblk[2]++;
        } else {
            s->err = "block type 3";
            return -1;
        }
    } while (!last);
    if (s->bit) { s->bit = 0; s->pos++; }
    return 0;
}

/* ------------------------------------------------------------ PNG */

static int unpaeth(int a, int b, int c)
{
    int p = a + b - c, pa = abs(p - a), pb = abs(p - b), pc = abs(p - c);
    if (pa <= pb && pa <= pc) return a;
    return pb <= pc ? b : c;
}

static uint8_t last_filters[4096];          /* decode(): each row's filter type */

/* Decode a PNG as the encoder must write it. Returns 0 and the pixels
 * (malloc'ed), or -1 with why. nblk: deflate blocks of each type. */
static int decode(const uint8_t *b, size_t n, int *w, int *h, int *ch, uint8_t **pix,
                  int nblk[3], char *why, size_t wl)
{
    static const uint8_t sig[8] = { 137, 80, 78, 71, 13, 10, 26, 10 };
    *pix = NULL;
    if (n < 8 || memcmp(b, sig, 8)) { snprintf(why, wl, "bad signature"); return -1; }
    size_t o = 8;
    uint8_t *z = NULL;
    size_t zn = 0;
    int seen_ihdr = 0, seen_iend = 0, bitdepth = 0, ctype = -1;
    while (o < n) {
        if (n - o < 12) { snprintf(why, wl, "truncated chunk at %zu", o); free(z); return -1; }
        uint32_t len = be32(b + o);
        if (len > n - o - 12) { snprintf(why, wl, "chunk length %u too big", len); free(z); return -1; }
        const uint8_t *type = b + o + 4, *data = b + o + 8;
        uint32_t crc = be32(data + len);
        if (crc != crc_bitwise(type, len + 4)) {
            snprintf(why, wl, "bad CRC of %.4s", (const char *)type);
            free(z);
            return -1;
        }
        if (!memcmp(type, "IHDR", 4)) {
            if (o != 8 || len != 13) { snprintf(why, wl, "IHDR misplaced"); free(z); return -1; }
            *w = (int)be32(data);
            *h = (int)be32(data + 4);
            bitdepth = data[8];
            ctype = data[9];
            if (data[10] || data[11] || data[12]) { snprintf(why, wl, "IHDR methods"); return -1; }
            seen_ihdr = 1;
        } else if (!memcmp(type, "IDAT", 4)) {
            uint8_t *nz = realloc(z, zn + len + 1);
            if (!nz) { free(z); return -1; }
            z = nz;
            memcpy(z + zn, data, len);
            zn += len;
        } else if (!memcmp(type, "IEND", 4)) {
            seen_iend = 1;
            if (o + 12 + len != n) { snprintf(why, wl, "data after IEND"); free(z); return -1; }
        } else {
            snprintf(why, wl, "unexpected chunk %.4s", (const char *)type);
            free(z);
            return -1;
        }
        o += 12 + len;
    }
    if (!seen_ihdr || !seen_iend || !z) { snprintf(why, wl, "missing chunk"); free(z); return -1; }
    if (bitdepth != 8 || (ctype != 0 && ctype != 2)) { snprintf(why, wl, "format"); free(z); return -1; }
    *ch = ctype == 0 ? 1 : 3;
    /* zlib: CMF FLG, deflate with a window <= 32K, check bits, no dictionary. */
    if (zn < 6 || (z[0] & 15) != 8 || (z[0] >> 4) > 7 || ((z[0] << 8) | z[1]) % 31 ||
        (z[1] & 0x20)) {
        snprintf(why, wl, "zlib header");
        free(z);
        return -1;
    }
    inf s = { .in = z + 2, .n = zn - 2 };
    size_t row = (size_t)*w * *ch + 1, raw = row * *h;
    uint8_t *r = NULL;
    if (inflate_raw(&s)) { snprintf(why, wl, "inflate: %s", s.err); goto bad; }
    memcpy(nblk, s.nblk, sizeof s.nblk);
    r = s.out;
    if (s.on != raw) { snprintf(why, wl, "raw size %zu, expected %zu", s.on, raw); goto bad; }
    if (s.pos + 4 != s.n || be32(s.in + s.pos) != adler_slow(r, raw)) { snprintf(why, wl, "Adler-32"); goto bad; }
    /* undo the filters: a left, b up, c up-left (zero outside the image) */
    size_t rb = row - 1, bpp = (size_t)*ch;
    *pix = malloc(raw ? raw : 1);
    for (int y = 0; y < *h; y++) {
        int f = r[y * row];
        if (y < 4096) last_filters[y] = (uint8_t)f;
        if (f > 4) { snprintf(why, wl, "filter %d", f); free(*pix); *pix = NULL; goto bad; }
        uint8_t *cur = *pix + y * rb;
        const uint8_t *up = y ? cur - rb : NULL, *src = r + y * row + 1;
        for (size_t i = 0; i < rb; i++) {
            int a = i >= bpp ? cur[i - bpp] : 0, bu = up ? up[i] : 0, c = up && i >= bpp ? up[i - bpp] : 0;
            int pred = f == 0 ? 0 : f == 1 ? a : f == 2 ? bu : f == 3 ? (a + bu) / 2 : unpaeth(a, bu, c);
            cur[i] = (uint8_t)(src[i] + pred);
        }
    }
    free(r);
    free(z);
    return 0;
bad:
    free(s.out);
    free(z);
    return -1;
}

static uint8_t *pattern(int w, int h, int ch, unsigned seed)
{
    uint8_t *p = malloc((size_t)w * h * ch);
    uint32_t s = seed;
    for (size_t i = 0; i < (size_t)w * h * ch; i++) {
        s = s * 1664525u + 1013904223u;
        p[i] = (uint8_t)(i % 7 == 0 ? s >> 24 : (i * 31) & 0xFF);
    }
    return p;
}

static int write_file(const char *path, const uint8_t *b, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (!f) return -1;
    size_t k = fwrite(b, 1, n, f);
    return fclose(f) || k != n ? -1 : 0;
}

static uint8_t *slurp_file(const char *path, size_t *n)
{
    *n = 0;
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    size_t cap = 4096;
    uint8_t *b = malloc(cap);
    size_t k;
    while ((k = fread(b + *n, 1, cap - *n, f)) > 0) {
        *n += k;
        if (*n == cap) b = realloc(b, cap *= 2);
    }
    fclose(f);
    return b;
}

/* Rows of the last decoded image whose filter is not the one of least
 * sum of |residual as a signed byte| (ties to the lower type): the sums
 * recomputed here from the pixels, per filter, by PNG's definitions. */
static int min_sum_rows(const uint8_t *p, int w, int h, int ch)
{
    int bad = 0;
    size_t rb = (size_t)w * ch;
    for (int y = 0; y < h && y < 4096; y++) {
        long sum[5] = { 0 };
        for (int f = 0; f < 5; f++)
            for (size_t i = 0; i < rb; i++) {
                int x = p[y * rb + i];
                int a = i >= (size_t)ch ? p[y * rb + i - ch] : 0;
                int b = y ? p[(y - 1) * rb + i] : 0;
                int c = y && i >= (size_t)ch ? p[(y - 1) * rb + i - ch] : 0;
                int pred = f == 0 ? 0 : f == 1 ? a : f == 2 ? b : f == 3 ? (a + b) / 2 : unpaeth(a, b, c);
                int r = (int8_t)(uint8_t)(x - pred);
                sum[f] += r < 0 ? -r : r;
            }
        int best = 0;
        for (int f = 1; f < 5; f++)
            if (sum[f] < sum[best]) best = f;
        bad += last_filters[y] != best;
    }
    return bad;
}

static void png_roundtrip(void)
{
    static const int sz[][3] = {
        { 1, 1, 1 }, { 1, 1, 3 }, { 3, 2, 1 }, { 5, 4, 3 }, { 17, 9, 3 },
        { 300, 300, 1 },            /* 90 300 raw bytes: two stored blocks */
        { 200, 150, 3 },            /* 90 150 */
        { 65534, 1, 1 },            /* raw 65535: exactly one full block */
        { 65535, 1, 1 },            /* raw 65536: one full block and one byte */
        { 512, 512, 3 },
    };
    for (size_t k = 0; k < sizeof sz / sizeof sz[0]; k++) {
        int w = sz[k][0], h = sz[k][1], ch = sz[k][2];
        uint8_t *p = pattern(w, h, ch, (unsigned)k + 1), *out = NULL, *dec = NULL;
        size_t len = 0;
        TST_EQ_INT(scn_png_encode(w, h, ch, p, &out, &len), 0);
        int dw = 0, dh = 0, dch = 0, nb[3] = { 0 };
        char why[128] = "";
        int rc = decode(out, len, &dw, &dh, &dch, &dec, nb, why, sizeof why);
        TST_CHECK(rc == 0, "%dx%dx%d: %s", w, h, ch, why);
        if (!rc) {
            TST_EQ_INT(dw, w);
            TST_EQ_INT(dh, h);
            TST_EQ_INT(dch, ch);
            TST_CHECK(!memcmp(dec, p, (size_t)w * h * ch), "%dx%dx%d: pixels differ", w, h, ch);
            TST_EQ_INT(min_sum_rows(p, w, h, ch), 0);
            /* never much above the stored form (a block of at most 32768
             * tokens falls back to stored bytes: 5 bytes and a partial one
             * per block); the pattern is 6/7 a ramp, so big images shrink
             * to well under half */
            size_t raw = ((size_t)w * ch + 1) * h, frame = 8 + 36 + 13 + 6;
            TST_CHECK(len <= frame + raw + 6 * (raw / 32768 + 1), "%dx%dx%d: %zu bytes for %zu raw", w, h, ch, len, raw);
            if (raw > 50000) TST_CHECK(len < raw / 2, "%dx%dx%d: %zu bytes for %zu raw", w, h, ch, len, raw);
        }
        free(p);
        free(out);
        free(dec);
    }
    /* A flat image (one colour) compresses to almost nothing: one filter
     * byte and one repeated pixel per row. */
    uint8_t *flat = malloc(512 * 512 * 3);
    for (size_t i = 0; i < 512 * 512; i++) { flat[3 * i] = 60; flat[3 * i + 1] = 180; flat[3 * i + 2] = 75; }
    uint8_t *fo = NULL, *fd = NULL;
    size_t fl = 0;
    TST_EQ_INT(scn_png_encode(512, 512, 3, flat, &fo, &fl), 0);
    int fw, fh, fch, fnb[3];
    char fwhy[128] = "";
    TST_CHECK(decode(fo, fl, &fw, &fh, &fch, &fd, fnb, fwhy, sizeof fwhy) == 0, "flat: %s", fwhy);
    TST_CHECK(fd && !memcmp(fd, flat, 512 * 512 * 3), "flat: pixels differ");
    TST_EQ_INT(min_sum_rows(flat, 512, 512, 3), 0);
    TST_CHECK(fl < 4000, "flat 512x512: %zu bytes", fl);
    free(flat);
    free(fo);
    free(fd);
    /* A render's shape: black around a shaded disc with some noise (rows
     * all black, rows black at both ends, rows alike), grey and RGB. */
    for (int ch = 1; ch <= 3; ch += 2) {
        int w = 301, h = 203;
        uint8_t *d = calloc((size_t)w * h * ch, 1), *o = NULL, *dd = NULL;
        uint32_t st = 5;
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++) {
                double dx = (x - 150) / 120.0, dy = (y - 100) / 80.0;
                if (dx * dx + dy * dy > 1) continue;
                st = st * 1664525u + 1013904223u;
                for (int k = 0; k < ch; k++)
                    d[((size_t)y * w + x) * ch + k] = (uint8_t)(40 + 150 * (1 - dx * dx - dy * dy) + 30 * k + (st >> 30));
            }
        size_t ol = 0;
        TST_EQ_INT(scn_png_encode(w, h, ch, d, &o, &ol), 0);
        int dw, dh, dch, dnb[3];
        char dwhy[128] = "";
        TST_CHECK(decode(o, ol, &dw, &dh, &dch, &dd, dnb, dwhy, sizeof dwhy) == 0, "disc: %s", dwhy);
        TST_CHECK(dd && dw == w && dh == h && !memcmp(dd, d, (size_t)w * h * ch), "disc %d: pixels differ", ch);
        TST_EQ_INT(min_sum_rows(d, w, h, ch), 0);
        TST_CHECK(ol < (size_t)w * h * ch / 3, "disc %d: %zu bytes", ch, ol);
        free(d);
        free(o);
        free(dd);
    }
    /* Same input, same bytes. */
    uint8_t *p = pattern(7, 5, 3, 9), *a, *b;
    size_t la, lb;
    scn_png_encode(7, 5, 3, p, &a, &la);
    scn_png_encode(7, 5, 3, p, &b, &lb);
    TST_CHECK(la == lb && !memcmp(a, b, la), "not deterministic");
    free(a); free(b);
    /* Bad arguments. */
    uint8_t *o = (uint8_t *)1;
    size_t ol = 1;
    TST_EQ_INT(scn_png_encode(0, 5, 1, p, &o, &ol), -1);
    TST_CHECK(o == NULL && ol == 0, "outputs cleared on error");
    TST_EQ_INT(scn_png_encode(5, -1, 1, p, &o, &ol), -1);
    TST_EQ_INT(scn_png_encode(5, 5, 2, p, &o, &ol), -1);
    TST_EQ_INT(scn_png_encode(5, 5, 4, p, &o, &ol), -1);
    free(p);
}

/* ------------------------------------------------------------ deflate */

typedef struct zcase { const char *name; uint8_t *d; size_t n; } zcase;

/* Inputs of known character: empty, one byte, a long run, random bytes,
 * a short text, a long repetitive text, and literals of Fibonacci
 * frequencies (their Huffman tree is 24 deep: lengths must be limited). */
static int zcases(zcase *c)
{
    int k = 0;
    c[k++] = (zcase){ "empty", calloc(1, 1), 0 };
    c[k] = (zcase){ "one", malloc(1), 1 }; c[k++].d[0] = 'x';
    c[k] = (zcase){ "zeros", calloc(200000, 1), 200000 }; k++;
    c[k] = (zcase){ "random", malloc(100000), 100000 };
    uint32_t st = 12345;
    for (size_t i = 0; i < 100000; i++) { st = st * 1664525u + 1013904223u; c[k].d[i] = (uint8_t)(st >> 24); }
    k++;
    const char *hello = "hello, hello, hello world";
    c[k] = (zcase){ "hello", (uint8_t *)strdup(hello), strlen(hello) }; k++;
    static const char *words[] = { "span ", "unit ", "horner ", "cubic ", "node ", "pixel ", "degree ", "\n" };
    c[k] = (zcase){ "text", malloc(300000), 0 };
    st = 7;
    while (c[k].n < 299990) {
        st = st * 1664525u + 1013904223u;
        const char *w = words[(st >> 24) % 8];
        memcpy(c[k].d + c[k].n, w, strlen(w));
        c[k].n += strlen(w);
    }
    k++;
    /* 25 symbols, symbol i occurring fib(i+1) times (1, 1, 2, 3, 5, ...),
     * in an order that repeats nothing usable for LZ77 at level 0 */
    size_t fib[25], tot = 0;
    fib[0] = fib[1] = 1;
    for (int i = 2; i < 25; i++) fib[i] = fib[i - 1] + fib[i - 2];
    for (int i = 0; i < 25; i++) tot += fib[i];
    c[k] = (zcase){ "fibonacci", malloc(tot), tot };
    size_t left[25], o = 0;
    memcpy(left, fib, sizeof fib);
    st = 99;
    while (o < tot) {
        st = st * 1664525u + 1013904223u;
        size_t r = (st >> 8) % (tot - o);
        int i = 0;
        while (r >= left[i]) r -= left[i++];
        left[i]--;
        c[k].d[o++] = (uint8_t)('A' + i);
    }
    k++;
    return k;
}

static void deflate_inflate(void)
{
    zcase c[8];
    int nc = zcases(c);
    for (int i = 0; i < nc; i++)
        for (int level = 0; level <= 2; level++) {
            uint8_t *z = NULL, *z2 = NULL;
            size_t zn = 0, zn2 = 0;
            TST_EQ_INT(scn_deflate(c[i].d, c[i].n, level, &z, &zn), 0);
            TST_EQ_INT(scn_deflate(c[i].d, c[i].n, level, &z2, &zn2), 0);
            TST_CHECK(zn == zn2 && !memcmp(z, z2, zn), "%s level %d: not deterministic", c[i].name, level);
            inf s = { .in = z, .n = zn };
            int rc = inflate_raw(&s);
            TST_CHECK(rc == 0, "%s level %d: %s", c[i].name, level, s.err);
            TST_CHECK(!rc && s.on == c[i].n && (!c[i].n || !memcmp(s.out, c[i].d, c[i].n)),
                      "%s level %d: %zu bytes back for %zu", c[i].name, level, s.on, c[i].n);
            TST_CHECK(s.pos == zn, "%s level %d: %zu bytes unused", c[i].name, level, zn - s.pos);
            const char *nm = c[i].name;
            /* what each input must come out as */
            if (!strcmp(nm, "random")) {
                TST_CHECK(s.nblk[1] == 0 && s.nblk[2] == 0, "random level %d: compressed blocks", level);
                TST_CHECK(zn <= c[i].n + 5 * (c[i].n / 32768 + 1) + 1, "random level %d: %zu bytes", level, zn);
            }
            if (!strcmp(nm, "hello") && level)
                TST_CHECK(s.nblk[1] == 1 && zn < c[i].n, "hello level %d: %d fixed blocks, %zu bytes", level, s.nblk[1], zn);
            if (!strcmp(nm, "zeros") && level) TST_CHECK(zn < 400, "zeros level %d: %zu bytes", level, zn);
            if (!strcmp(nm, "text")) {
                TST_CHECK(s.nblk[2] > 0, "text level %d: no dynamic block", level);
                /* 8 symbols of 4..8 bytes: even literals alone need < 4 bits */
                TST_CHECK(zn < c[i].n / 2, "text level %d: %zu bytes", level, zn);
                /* a word of 3 bits' choice is a match: ~20 bits a word (zlib -1: 18%) */
                if (level) TST_CHECK(zn < c[i].n / 5, "text level %d: %zu bytes", level, zn);
            }
            if (!strcmp(nm, "fibonacci") && level == 0) {
                TST_CHECK(s.nblk[2] > 0 && s.maxlen == 15, "fibonacci: %d dynamic blocks, longest code %d",
                          s.nblk[2], s.maxlen);
                /* entropy of the Fibonacci source is under 2 bits a symbol */
                TST_CHECK(zn < c[i].n / 3, "fibonacci: %zu bytes for %zu", zn, c[i].n);
            }
            free(z);
            free(z2);
            free(s.out);
        }
    for (int i = 0; i < nc; i++) free(c[i].d);
}

static int have(const char *tool)
{
    char cmd[256];
    snprintf(cmd, sizeof cmd, "command -v %s >/dev/null 2>&1", tool);
    return system(cmd) == 0;
}

/* pngcheck inflates the IDAT stream with zlib and checks every chunk:
 * ramps, pure noise (stored blocks), a flat image, a single pixel. */
static void png_pngcheck(void)
{
    /* the tools read the encoder's bytes, the same in every build */
    if (tst_asan_build()) TST_SKIP("runs in the plain build only");
    if (!have("pngcheck")) TST_SKIP("pngcheck not installed");
    char path[700], cmd[1600];
    static const int sz[][4] = { { 300, 250, 1, 0 }, { 300, 250, 3, 0 }, { 200, 200, 3, 1 }, { 512, 512, 3, 2 },
                                 { 1, 1, 1, 0 } };
    for (size_t k = 0; k < sizeof sz / sizeof sz[0]; k++) {
        int w = sz[k][0], h = sz[k][1], ch = sz[k][2];
        uint8_t *p = pattern(w, h, ch, 5), *out;
        uint32_t st = 3;
        for (size_t i = 0; i < (size_t)w * h * ch; i++) {
            st = st * 1664525u + 1013904223u;
            if (sz[k][3] == 1) p[i] = (uint8_t)(st >> 24);
            if (sz[k][3] == 2) p[i] = (uint8_t)(40 * (i % 3));
        }
        size_t len;
        TST_EQ_INT(scn_png_encode(w, h, ch, p, &out, &len), 0);
        snprintf(path, sizeof path, "%s/check%zu.png", tdir, k);
        TST_EQ_INT(write_file(path, out, len), 0);
        snprintf(cmd, sizeof cmd, "pngcheck -q '%s' >/dev/null 2>&1", path);
        TST_CHECK(system(cmd) == 0, "pngcheck rejects %s", path);
        free(p);
        free(out);
    }
}

/* python3's zlib inflates the IDAT stream and the script undoes the
 * filters; the pixels must be those encoded. zlib also inflates the raw
 * deflate streams of the inputs above, at every level. */
static void png_python_zlib(void)
{
    if (tst_asan_build()) TST_SKIP("runs in the plain build only");
    if (!have("python3")) TST_SKIP("python3 not installed");
    char script[700], cmd[3000];
    snprintf(script, sizeof script, "%s/py.py", tdir);
    FILE *f = fopen(script, "w");
    fputs("import sys, struct, zlib\n"
          "def png(path):\n"
          "    b = open(path, 'rb').read(); o, z = 8, b''\n"
          "    while o < len(b):\n"
          "        n, = struct.unpack('>I', b[o:o+4]); t = b[o+4:o+8]\n"
          "        if zlib.crc32(b[o+4:o+8+n]) & 0xffffffff != struct.unpack('>I', b[o+8+n:o+12+n])[0]:\n"
          "            sys.exit('crc')\n"
          "        if t == b'IHDR': w, h, bd, ct = struct.unpack('>IIBB', b[o+8:o+18])\n"
          "        if t == b'IDAT': z += b[o+8:o+8+n]\n"
          "        o += 12 + n\n"
          "    r = zlib.decompress(z); bpp = 1 if ct == 0 else 3; rb = w * bpp\n"
          "    out = bytearray(); up = bytearray(rb)\n"
          "    for y in range(h):\n"
          "        ft = r[y*(rb+1)]; cur = bytearray(r[y*(rb+1)+1:(y+1)*(rb+1)])\n"
          "        for i in range(rb):\n"
          "            a = cur[i-bpp] if i >= bpp else 0; u = up[i]; c = up[i-bpp] if i >= bpp else 0\n"
          "            if ft == 1: q = a\n"
          "            elif ft == 2: q = u\n"
          "            elif ft == 3: q = (a + u) // 2\n"
          "            elif ft == 4:\n"
          "                p = a + u - c; pa, pb, pc = abs(p - a), abs(p - u), abs(p - c)\n"
          "                q = a if pa <= pb and pa <= pc else (u if pb <= pc else c)\n"
          "            else: q = 0\n"
          "            cur[i] = (cur[i] + q) & 255\n"
          "        out += cur; up = cur\n"
          "    return bytes(out)\n"
          "if sys.argv[1] == 'png': open(sys.argv[3], 'wb').write(png(sys.argv[2]))\n"
          "else: open(sys.argv[3], 'wb').write(zlib.decompress(open(sys.argv[2], 'rb').read(), -15))\n", f);
    fclose(f);
    static const int sz[][3] = { { 123, 77, 3 }, { 64, 40, 1 }, { 1, 1, 3 } };
    for (size_t k = 0; k < sizeof sz / sizeof sz[0]; k++) {
        int w = sz[k][0], h = sz[k][1], ch = sz[k][2];
        uint8_t *p = pattern(w, h, ch, 11 + (unsigned)k), *out;
        size_t len, n = (size_t)w * h * ch;
        TST_EQ_INT(scn_png_encode(w, h, ch, p, &out, &len), 0);
        char png[700], rawp[700];
        snprintf(png, sizeof png, "%s/py%zu.png", tdir, k);
        snprintf(rawp, sizeof rawp, "%s/py%zu.raw", tdir, k);
        TST_EQ_INT(write_file(png, out, len), 0);
        snprintf(cmd, sizeof cmd, "python3 '%s' png '%s' '%s'", script, png, rawp);
        TST_CHECK(system(cmd) == 0, "python3 zlib failed: %s", cmd);
        size_t got = 0;
        uint8_t *r = slurp_file(rawp, &got);
        TST_CHECK(r && got == n && !memcmp(r, p, n), "%dx%dx%d: python3 reads other pixels (%zu bytes)", w, h, ch, got);
        free(r);
        free(p);
        free(out);
    }
    zcase c[8];
    int nc = zcases(c);
    for (int i = 0; i < nc; i++)
        for (int level = 0; level <= 2; level++) {
            uint8_t *z;
            size_t zn, got = 0;
            TST_EQ_INT(scn_deflate(c[i].d, c[i].n, level, &z, &zn), 0);
            char zp[700], rp[700];
            snprintf(zp, sizeof zp, "%s/%s%d.z", tdir, c[i].name, level);
            snprintf(rp, sizeof rp, "%s/%s%d.raw", tdir, c[i].name, level);
            TST_EQ_INT(write_file(zp, z, zn), 0);
            snprintf(cmd, sizeof cmd, "python3 '%s' raw '%s' '%s'", script, zp, rp);
            TST_CHECK(system(cmd) == 0, "python3 zlib failed: %s", cmd);
            uint8_t *r = slurp_file(rp, &got);
            TST_CHECK(r && got == c[i].n && (!got || !memcmp(r, c[i].d, got)), "%s level %d: python3 zlib gives %zu bytes",
                      c[i].name, level, got);
            free(r);
            free(z);
        }
    for (int i = 0; i < nc; i++) free(c[i].d);
}

static double lum(const uint8_t c[3]) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

static void heat_map(void)
{
    static const struct { double v; uint8_t rgb[3]; } K[] = {
        { 0.0, { 0, 0, 0 } }, { 0.25, { 0, 0, 255 } }, { 0.5, { 255, 0, 0 } },
        { 0.75, { 255, 255, 0 } }, { 1.0, { 255, 255, 255 } },
        { -3.0, { 0, 0, 0 } }, { 7.0, { 255, 255, 255 } }, { NAN, { 0, 0, 0 } } };
    for (size_t i = 0; i < sizeof K / sizeof K[0]; i++) {
        uint8_t c[3];
        scn_heat_rgb(K[i].v, c);
        TST_CHECK(!memcmp(c, K[i].rgb, 3), "v=%g: %d %d %d", K[i].v, c[0], c[1], c[2]);
    }
    /* Monotone in luminance over a fine sweep. */
    uint8_t prev[3];
    scn_heat_rgb(0, prev);
    int bad = 0;
    for (int i = 1; i <= 4000; i++) {
        uint8_t c[3];
        scn_heat_rgb(i / 4000.0, c);
        if (lum(c) < lum(prev)) bad++;
        memcpy(prev, c, 3);
    }
    TST_EQ_INT(bad, 0);
}

static void label_colours(void)
{
    uint8_t c[16][3];
    for (int i = 0; i < 16; i++) scn_label_rgb(i, c[i]);
    int close = 0;
    for (int i = 0; i < 16; i++) {
        int dist0 = c[i][0] + c[i][1] + c[i][2];
        TST_CHECK(dist0 > 60, "label %d too close to the black background", i);
        for (int j = 0; j < i; j++) {
            int d = abs(c[i][0] - c[j][0]) + abs(c[i][1] - c[j][1]) + abs(c[i][2] - c[j][2]);
            if (d < 60) close++;
        }
    }
    TST_EQ_INT(close, 0);
    uint8_t a[3];
    scn_label_rgb(17, a);
    TST_CHECK(!memcmp(a, c[1], 3), "labels repeat modulo 16");
}

int main(void)
{
    const char *t = getenv("TMPDIR");
    snprintf(tdir, sizeof tdir, "%s/test_png.XXXXXX", t && *t ? t : "/tmp");
    if (!mkdtemp(tdir)) { printf("FAIL test_png: mkdtemp: %s\n", strerror(errno)); return 1; }
    TST_RUN(png_roundtrip);
    TST_RUN(deflate_inflate);
    TST_RUN(png_pngcheck);
    TST_RUN(png_python_zlib);
    TST_RUN(heat_map);
    TST_RUN(label_colours);
    tst_rmtree(tdir);
    rmdir(tdir);
    TST_EXIT();
}
