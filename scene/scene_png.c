/* scene_png.c - PNG encoder and colour maps.
 *
 * The encoder writes the signature, IHDR (8-bit greyscale or RGB, no
 * interlace), one IDAT holding a zlib stream (scene_deflate.c's DEFLATE at
 * its fast level, then the Adler-32 of the filtered scanlines), and IEND.
 * Each scanline gets the filter (None, Sub, Up, Average, Paeth) whose
 * output has the least sum of absolute values taken as signed bytes, the
 * heuristic the PNG specification suggests (ties to the lower filter).
 *
 * CRC-32 (the polynomial 0xEDB88320, reflected, as PNG and zlib use) comes
 * from a 256-entry table built into a local array at each call: that costs
 * 2048 shift steps per image, and two threads encoding at once share no
 * state at all.
 */
#include "scene/scene.h"
#include <stdlib.h>
#include <string.h>
#include <math.h>

static void crc_table(uint32_t t[256])
{
    for (uint32_t n = 0; n < 256; n++) {
        uint32_t c = n;
        for (int k = 0; k < 8; k++) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
        t[n] = c;
    }
}

static uint32_t crc_update(const uint32_t t[256], uint32_t crc, const uint8_t *p, size_t n)
{
    for (size_t i = 0; i < n; i++) crc = t[(crc ^ p[i]) & 0xFF] ^ (crc >> 8);
    return crc;
}

static void put32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)(v >> 24); p[1] = (uint8_t)(v >> 16);
    p[2] = (uint8_t)(v >> 8);  p[3] = (uint8_t)v;
}

/* A chunk at out: length, type, data (already in place at out + 8), CRC
 * over type and data. Returns the chunk's total size. */
static size_t chunk_close(const uint32_t t[256], uint8_t *out, const char type[4], size_t n)
{
    put32(out, (uint32_t)n);
    memcpy(out + 4, type, 4);
    uint32_t crc = crc_update(t, 0xFFFFFFFFu, out + 4, n + 4) ^ 0xFFFFFFFFu;
    put32(out + 8 + n, crc);
    return n + 12;
}

static uint32_t adler32(const uint8_t *p, size_t n)
{
    uint32_t s1 = 1, s2 = 0;
    while (n) {
        size_t k = n < 5552 ? n : 5552;         /* no 32-bit overflow before the modulo */
        n -= k;
        while (k--) { s1 += *p++; s2 += s1; }
        s1 %= 65521;
        s2 %= 65521;
    }
    return s2 << 16 | s1;
}

/* Paeth's predictor with p - a = b - c and so on worked out, written with
 * plain selects so that the compiler needs no branches. */
static inline int paeth(int a, int b, int c)
{
    int pa = abs(b - c), pb = abs(a - c), pc = abs(a + b - 2 * c);
    int ab = pb <= pc ? b : c;
    return pa <= pb && pa <= pc ? a : ab;
}

/* |v| of a filtered byte read as signed */
static inline unsigned mag(int v)
{
    int t = (int8_t)(uint8_t)v;
    return (unsigned)(t < 0 ? -t : t);
}

/* The filter (0 None, 1 Sub, 2 Up, 3 Average, 4 Paeth) of least sum of
 * |signed byte| for row cur (prev: the row above, zeros for the first
 * row; bpp bytes per pixel), all five summed in one pass; ties to the
 * lower number. */
static int filter_pick(const uint8_t *cur, const uint8_t *prev, size_t n, size_t bpp)
{
    unsigned long s0 = 0, s1 = 0, s2 = 0, s3 = 0, s4 = 0;
    for (size_t i = 0; i < n; i++) {
        int x = cur[i], b = prev[i], a = 0, c = 0;
        if (i >= bpp) { a = cur[i - bpp]; c = prev[i - bpp]; }
        s0 += mag(x);
        s1 += mag(x - a);
        s2 += mag(x - b);
        s3 += mag(x - ((a + b) >> 1));
        s4 += mag(x - paeth(a, b, c));
    }
    unsigned long s[5] = { s0, s1, s2, s3, s4 };
    int best = 0;
    for (int f = 1; f < 5; f++)
        if (s[f] < s[best]) best = f;
    return best;
}

static void filter_row(int f, const uint8_t *cur, const uint8_t *prev, size_t n, size_t bpp, uint8_t *out)
{
    for (size_t i = 0; i < n; i++) {
        int b = prev[i], a = 0, c = 0;
        if (i >= bpp) { a = cur[i - bpp]; c = prev[i - bpp]; }
        int pred = f == 0 ? 0 : f == 1 ? a : f == 2 ? b : f == 3 ? (a + b) >> 1 : paeth(a, b, c);
        out[i] = (uint8_t)(cur[i] - pred);
    }
}

int scn_png_encode(int w, int h, int channels, const uint8_t *pix, uint8_t **out, size_t *len)
{
    *out = NULL;
    *len = 0;
    if (w <= 0 || h <= 0 || (channels != 1 && channels != 3) || !pix) return -1;
    /* Filtered scanlines: a filter byte and w*channels bytes per row. */
    size_t rb = (size_t)w * (size_t)channels, row = rb + 1;
    if (rb > SIZE_MAX / (size_t)h / 2) return -1;
    size_t raw = row * (size_t)h;
    uint8_t *f = malloc(raw), *zero = calloc(rb, 1);
    if (!f || !zero) { free(f); free(zero); return -1; }
    for (int y = 0; y < h; y++) {
        const uint8_t *cur = pix + (size_t)y * rb, *prev = y ? cur - rb : zero;
        uint8_t *dst = f + (size_t)y * row;
        dst[0] = (uint8_t)filter_pick(cur, prev, rb, (size_t)channels);
        filter_row(dst[0], cur, prev, rb, (size_t)channels, dst + 1);
    }
    free(zero);
    uint8_t *z = NULL;
    size_t zn = 0;
    int rc = scn_deflate(f, raw, 1, &z, &zn);
    uint32_t ad = adler32(f, raw);
    free(f);
    if (rc) return -1;
    size_t zlen = 2 + zn + 4;                   /* header, deflate, Adler-32 */
    if (zlen > 0x7FFFFFFFu) { free(z); return -1; }     /* PNG chunk length limit */
    size_t total = 8 + (12 + 13) + (12 + zlen) + 12;
    uint8_t *b = malloc(total);
    if (!b) { free(z); return -1; }
    uint32_t t[256];
    crc_table(t);

    static const uint8_t sig[8] = { 0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n' };
    size_t o = 0;
    memcpy(b, sig, 8);
    o = 8;

    uint8_t *ih = b + o + 8;
    put32(ih, (uint32_t)w);
    put32(ih + 4, (uint32_t)h);
    ih[8] = 8;                                  /* bit depth */
    ih[9] = channels == 1 ? 0 : 2;              /* colour type: grey / RGB */
    ih[10] = 0; ih[11] = 0; ih[12] = 0;         /* deflate, adaptive filtering, no interlace */
    o += chunk_close(t, b + o, "IHDR", 13);

    /* IDAT: zlib header 0x78 0x5E (deflate, 32K window, no dictionary,
     * level "fast"; 0x785E is a multiple of 31 as the header check demands). */
    uint8_t *zd = b + o + 8;
    zd[0] = 0x78;
    zd[1] = 0x5E;
    memcpy(zd + 2, z, zn);
    put32(zd + 2 + zn, ad);
    free(z);
    o += chunk_close(t, b + o, "IDAT", zlen);
    o += chunk_close(t, b + o, "IEND", 0);
    *out = b;
    *len = o;
    return 0;
}

/* ------------------------------------------------------------ colour maps */

/* Heat map: black -> blue -> red -> yellow -> white at v = 0, 1/4, 1/2,
 * 3/4, 1, linear in 8-bit values between. Luminance (Rec. 709 weights
 * 0.2126 R + 0.7152 G + 0.0722 B) rises along every segment: blue 0.07 ->
 * red 0.21 -> yellow 0.93 -> white 1, and inside a segment it moves
 * linearly between its ends, so the map is monotone in luminance. */
void scn_heat_rgb(double v, uint8_t rgb[3])
{
    if (!(v > 0.0)) v = 0.0;                    /* also NaN */
    if (v > 1.0) v = 1.0;
    double s = v * 4.0;
    int i = (int)s;
    if (i > 3) i = 3;
    /* One integer step k = 0..255 along the segment; in blue -> red the
     * two channels move together (R = k, B = 255 - k), so rounding never
     * lets luminance step back. */
    uint8_t k = (uint8_t)lround((s - i) * 255.0);
    switch (i) {
    case 0: rgb[0] = 0;   rgb[1] = 0;   rgb[2] = k;   break;      /* black -> blue */
    case 1: rgb[0] = k;   rgb[1] = 0;   rgb[2] = (uint8_t)(255 - k); break;  /* blue -> red */
    case 2: rgb[0] = 255; rgb[1] = k;   rgb[2] = 0;   break;      /* red -> yellow */
    default: rgb[0] = 255; rgb[1] = 255; rgb[2] = k;  break;      /* yellow -> white */
    }
}

/* Sixteen colours that stay apart from each other and from the black
 * background; labels repeat modulo 16 (negative labels are grey). */
void scn_label_rgb(int label, uint8_t rgb[3])
{
    static const uint8_t pal[16][3] = {
        { 128, 128, 128 }, { 230,  25,  75 }, {  60, 180,  75 }, { 255, 225,  25 },
        {   0, 130, 200 }, { 245, 130,  48 }, { 145,  30, 180 }, {  70, 240, 240 },
        { 240,  50, 230 }, { 210, 245,  60 }, { 250, 190, 212 }, {   0, 128, 128 },
        { 220, 190, 255 }, { 170, 110,  40 }, { 255, 250, 200 }, { 128,   0,   0 },
    };
    const uint8_t *p = label < 0 ? pal[0] : pal[label % 16];
    rgb[0] = p[0]; rgb[1] = p[1]; rgb[2] = p[2];
}
