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
#if defined(__SSE2__)
#include <emmintrin.h>            /* baseline on x86-64: no run-time choice needed */
#endif

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

/* The five residuals of byte x with neighbours a (left), b (up), c (up
 * left) added into the sums. */
#define FILTER_SUMS(x, a, b, c) do { \
        s0 += mag(x); s1 += mag((x) - (a)); s2 += mag((x) - (b)); \
        s3 += mag((x) - (((a) + (b)) >> 1)); s4 += mag((x) - paeth(a, b, c)); } while (0)

/* The filter (0 None, 1 Sub, 2 Up, 3 Average, 4 Paeth) of least sum of
 * |signed byte| over bytes [i0, i1) of row cur (prev: the row above, zeros
 * for the first row; bpp bytes per pixel), all five summed in one pass;
 * ties to the lower number. Outside [i0, i1) every residual is 0. */
#if defined(__SSE2__)
/* |v| of 16 signed bytes, as unsigned bytes: min(v, -v) (|-128| = 128). */
static inline __m128i absb(__m128i v) { return _mm_min_epu8(v, _mm_sub_epi8(_mm_setzero_si128(), v)); }
static inline __m128i abs16(__m128i v) { return _mm_max_epi16(v, _mm_sub_epi16(_mm_setzero_si128(), v)); }

/* paeth() on eight 16-bit lanes, by masks instead of branches. */
static inline __m128i paeth8(__m128i a, __m128i b, __m128i c)
{
    __m128i pa = abs16(_mm_sub_epi16(b, c)), pb = abs16(_mm_sub_epi16(a, c));
    __m128i pc = abs16(_mm_sub_epi16(_mm_add_epi16(a, b), _mm_add_epi16(c, c)));
    __m128i nota = _mm_or_si128(_mm_cmpgt_epi16(pa, pb), _mm_cmpgt_epi16(pa, pc));
    __m128i usec = _mm_cmpgt_epi16(pb, pc);
    __m128i bc = _mm_or_si128(_mm_and_si128(usec, c), _mm_andnot_si128(usec, b));
    return _mm_or_si128(_mm_andnot_si128(nota, a), _mm_and_si128(nota, bc));
}

/* The five sums over bytes [i, i + 16k) with i >= bpp, 16 at a time: the
 * same integers as FILTER_SUMS, so the same choice. Returns where it
 * stopped. */
static size_t filter_sums16(const uint8_t *cur, const uint8_t *prev, size_t i, size_t i1, size_t bpp,
                            unsigned long s[5])
{
    const __m128i z = _mm_setzero_si128(), one = _mm_set1_epi8(1);
    __m128i acc[5] = { z, z, z, z, z };
    for (; i + 16 <= i1; i += 16) {
        __m128i x = _mm_loadu_si128((const __m128i *)(cur + i)), a = _mm_loadu_si128((const __m128i *)(cur + i - bpp));
        __m128i b = _mm_loadu_si128((const __m128i *)(prev + i)), c = _mm_loadu_si128((const __m128i *)(prev + i - bpp));
        /* floor((a + b) / 2): pavgb rounds up, less the odd bit */
        __m128i avg = _mm_sub_epi8(_mm_avg_epu8(a, b), _mm_and_si128(_mm_xor_si128(a, b), one));
        __m128i p = _mm_packus_epi16(paeth8(_mm_unpacklo_epi8(a, z), _mm_unpacklo_epi8(b, z), _mm_unpacklo_epi8(c, z)),
                                     paeth8(_mm_unpackhi_epi8(a, z), _mm_unpackhi_epi8(b, z), _mm_unpackhi_epi8(c, z)));
        acc[0] = _mm_add_epi64(acc[0], _mm_sad_epu8(absb(x), z));
        acc[1] = _mm_add_epi64(acc[1], _mm_sad_epu8(absb(_mm_sub_epi8(x, a)), z));
        acc[2] = _mm_add_epi64(acc[2], _mm_sad_epu8(absb(_mm_sub_epi8(x, b)), z));
        acc[3] = _mm_add_epi64(acc[3], _mm_sad_epu8(absb(_mm_sub_epi8(x, avg)), z));
        acc[4] = _mm_add_epi64(acc[4], _mm_sad_epu8(absb(_mm_sub_epi8(x, p)), z));
    }
    for (int f = 0; f < 5; f++) {
        uint64_t t[2];
        _mm_storeu_si128((__m128i *)t, acc[f]);
        s[f] += (unsigned long)(t[0] + t[1]);
    }
    return i;
}
#endif

static int filter_pick(const uint8_t *cur, const uint8_t *prev, size_t i0, size_t i1, size_t bpp)
{
    unsigned long s0 = 0, s1 = 0, s2 = 0, s3 = 0, s4 = 0;
    size_t i = i0;
    for (; i < i1 && i < bpp; i++) FILTER_SUMS(cur[i], 0, prev[i], 0);
#if defined(__SSE2__)
    unsigned long v[5] = { 0, 0, 0, 0, 0 };
    i = filter_sums16(cur, prev, i, i1, bpp, v);
    s0 += v[0]; s1 += v[1]; s2 += v[2]; s3 += v[3]; s4 += v[4];
#endif
    for (; i < i1; i++) FILTER_SUMS(cur[i], cur[i - bpp], prev[i], prev[i - bpp]);
    unsigned long s[5] = { s0, s1, s2, s3, s4 };
    int best = 0;
    for (int f = 1; f < 5; f++)
        if (s[f] < s[best]) best = f;
    return best;
}

/* Row cur filtered with f into out, bytes [i0, i1); a loop per filter,
 * the first pixel (no left neighbour) apart. */
static void filter_row(int f, const uint8_t *cur, const uint8_t *prev, size_t i0, size_t i1, size_t bpp,
                       uint8_t *out)
{
    size_t i = i0;
    for (; i < i1 && i < bpp; i++) {
        int b = prev[i];
        out[i] = (uint8_t)(cur[i] - (f == 0 || f == 1 ? 0 : f == 3 ? b >> 1 : b));   /* Paeth(0, b, 0) = b */
    }
    switch (f) {
    case 0: if (i < i1) memcpy(out + i, cur + i, i1 - i); break;
    case 1: for (; i < i1; i++) out[i] = (uint8_t)(cur[i] - cur[i - bpp]); break;
    case 2: for (; i < i1; i++) out[i] = (uint8_t)(cur[i] - prev[i]); break;
    case 3: for (; i < i1; i++) out[i] = (uint8_t)(cur[i] - ((cur[i - bpp] + prev[i]) >> 1)); break;
    default:
        for (; i < i1; i++) out[i] = (uint8_t)(cur[i] - paeth(cur[i - bpp], prev[i], prev[i - bpp]));
        break;
    }
}

/* First and one past the last non-zero byte of p[0..n) (n, n when none). */
static void nonzero_span(const uint8_t *p, size_t n, size_t *first, size_t *end)
{
    size_t i = 0, j = n;
    while (i < n && !p[i]) i++;
    while (j > i && !p[j - 1]) j--;
    *first = i;
    *end = i < n ? j : n;
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
    size_t f1 = rb, e1 = rb;                    /* the row above's span: none */
    for (int y = 0; y < h; y++) {
        const uint8_t *cur = pix + (size_t)y * rb, *prev = y ? cur - rb : zero;
        uint8_t *dst = f + (size_t)y * row;
        /* Outside the bytes where this row or the one above is non-zero
         * (and a pixel right of them) every input of every filter is 0, so
         * every residual is: the sums and the output need only that span.
         * An all-zero row (the background) thus picks None. */
        size_t f0, e0;
        nonzero_span(cur, rb, &f0, &e0);
        size_t i0 = f0 < f1 ? f0 : f1, i1 = f0 == rb ? e1 : f1 == rb ? e0 : e0 > e1 ? e0 : e1;
        f1 = f0;
        e1 = e0;
        if (i0 >= i1) i0 = i1 = 0;
        else i1 = i1 + (size_t)channels < rb ? i1 + (size_t)channels : rb;
        dst[0] = (uint8_t)(i0 < i1 ? filter_pick(cur, prev, i0, i1, (size_t)channels) : 0);
        memset(dst + 1, 0, rb);
        filter_row(dst[0], cur, prev, i0, i1, (size_t)channels, dst + 1);
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
