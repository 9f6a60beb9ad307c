/* scene_png.c - PNG encoder and colour maps.
 *
 * The encoder writes the smallest valid PNG that needs no compressor: the
 * signature, IHDR (8-bit greyscale or RGB, no interlace), one IDAT holding a
 * zlib stream of *stored* deflate blocks (each at most 65535 bytes, as the
 * 16-bit LEN field allows) and the Adler-32 of the raw scanlines, then IEND.
 * Every scanline starts with filter byte 0 (None). Images are therefore
 * about as large as the raw pixels; they are written for inspection, not
 * for size.
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

int scn_png_encode(int w, int h, int channels, const uint8_t *pix, uint8_t **out, size_t *len)
{
    *out = NULL;
    *len = 0;
    if (w <= 0 || h <= 0 || (channels != 1 && channels != 3) || !pix) return -1;
    /* Raw scanlines: a filter byte and w*channels bytes per row. */
    size_t row = (size_t)w * (size_t)channels + 1;
    if (row - 1 > SIZE_MAX / (size_t)h / 2) return -1;
    size_t raw = row * (size_t)h;
    size_t nblocks = raw / 65535 + (raw % 65535 != 0);
    size_t zlen = 2 + raw + 5 * nblocks + 4;            /* header, blocks, Adler-32 */
    if (zlen > 0x7FFFFFFFu) return -1;                  /* PNG chunk length limit */
    size_t total = 8 + (12 + 13) + (12 + zlen) + 12;
    uint8_t *b = malloc(total);
    if (!b) return -1;
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

    /* IDAT: zlib header 0x78 0x01 (deflate, 32K window, no dictionary,
     * "fastest"; 0x7801 is a multiple of 31 as the header check demands). */
    uint8_t *z = b + o + 8;
    size_t zo = 0;
    z[zo++] = 0x78;
    z[zo++] = 0x01;
    uint32_t s1 = 1, s2 = 0;                    /* Adler-32 */
    size_t done = 0;                            /* raw bytes emitted */
    size_t x = 0;                               /* position in the current scanline */
    const uint8_t *src = pix;
    while (done < raw) {
        size_t n = raw - done < 65535 ? raw - done : 65535;
        z[zo++] = done + n == raw;              /* BFINAL, BTYPE = 00 (stored) */
        z[zo++] = (uint8_t)n;
        z[zo++] = (uint8_t)(n >> 8);
        z[zo++] = (uint8_t)~n;
        z[zo++] = (uint8_t)(~n >> 8);
        for (size_t k = 0; k < n; k++) {
            uint8_t byte = x == 0 ? 0 : *src++;
            if (++x == row) x = 0;
            z[zo++] = byte;
            s1 += byte;
            if (s1 >= 65521) s1 -= 65521;
            s2 += s1;
            if (s2 >= 65521) s2 -= 65521;
        }
        done += n;
    }
    put32(z + zo, (s2 << 16) | s1);
    zo += 4;
    o += chunk_close(t, b + o, "IDAT", zo);
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
