/* test_png.c - the PNG encoder against an independent minimal decoder
 * written here (chunk walk, CRC-32 recomputed bit by bit, zlib header,
 * stored deflate blocks, Adler-32, filter bytes), plus pngcheck and
 * python3's zlib as outside references when they are installed; and the
 * colour maps. */
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

/* Decode a PNG as the encoder must write it. Returns 0 and the pixels
 * (malloc'ed), or -1 with why. Also reports the number of deflate blocks. */
static int decode(const uint8_t *b, size_t n, int *w, int *h, int *ch, uint8_t **pix,
                  int *nblocks, char *why, size_t wl)
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
    size_t row = (size_t)*w * *ch + 1, raw = row * *h, got = 0, zo = 2;
    uint8_t *r = malloc(raw ? raw : 1);
    *nblocks = 0;
    int final = 0;
    while (!final) {
        if (zo + 5 > zn) { snprintf(why, wl, "truncated deflate"); goto bad; }
        uint8_t hdr = z[zo];
        final = hdr & 1;
        if (((hdr >> 1) & 3) != 0) { snprintf(why, wl, "not a stored block"); goto bad; }
        unsigned len = z[zo + 1] | z[zo + 2] << 8, nlen = z[zo + 3] | z[zo + 4] << 8;
        if ((len ^ 0xFFFFu) != nlen) { snprintf(why, wl, "LEN/NLEN"); goto bad; }
        zo += 5;
        if (zo + len > zn || got + len > raw) { snprintf(why, wl, "block too long"); goto bad; }
        memcpy(r + got, z + zo, len);
        got += len;
        zo += len;
        ++*nblocks;
    }
    if (got != raw) { snprintf(why, wl, "raw size %zu, expected %zu", got, raw); goto bad; }
    if (zo + 4 != zn || be32(z + zo) != adler_slow(r, raw)) { snprintf(why, wl, "Adler-32"); goto bad; }
    *pix = malloc(raw ? raw : 1);
    for (int y = 0; y < *h; y++) {
        if (r[y * row] != 0) { snprintf(why, wl, "filter %d", r[y * row]); free(*pix); *pix = NULL; goto bad; }
        memcpy(*pix + y * (row - 1), r + y * row + 1, row - 1);
    }
    free(r);
    free(z);
    return 0;
bad:
    free(r);
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
        int dw = 0, dh = 0, dch = 0, nb = 0;
        char why[128] = "";
        int rc = decode(out, len, &dw, &dh, &dch, &dec, &nb, why, sizeof why);
        TST_CHECK(rc == 0, "%dx%dx%d: %s", w, h, ch, why);
        if (!rc) {
            TST_EQ_INT(dw, w);
            TST_EQ_INT(dh, h);
            TST_EQ_INT(dch, ch);
            size_t raw = ((size_t)w * ch + 1) * h;
            TST_EQ_INT(nb, (raw + 65534) / 65535);
            TST_CHECK(!memcmp(dec, p, (size_t)w * h * ch), "%dx%dx%d: pixels differ", w, h, ch);
            /* size: signature, 3 chunk frames, IHDR, zlib 2+4, 5 per block */
            TST_EQ_INT(len, 8 + 36 + 13 + 6 + 5 * (size_t)nb + raw);
        }
        free(p);
        free(out);
        free(dec);
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

static int have(const char *tool)
{
    char cmd[256];
    snprintf(cmd, sizeof cmd, "command -v %s >/dev/null 2>&1", tool);
    return system(cmd) == 0;
}

static void png_pngcheck(void)
{
    if (!have("pngcheck")) TST_SKIP("pngcheck not installed");
    char path[700], cmd[1600];
    for (int ch = 1; ch <= 3; ch += 2) {
        uint8_t *p = pattern(300, 250, ch, 5), *out;
        size_t len;
        TST_EQ_INT(scn_png_encode(300, 250, ch, p, &out, &len), 0);
        snprintf(path, sizeof path, "%s/check%d.png", tdir, ch);
        TST_EQ_INT(write_file(path, out, len), 0);
        snprintf(cmd, sizeof cmd, "pngcheck -q '%s' >/dev/null 2>&1", path);
        TST_CHECK(system(cmd) == 0, "pngcheck rejects %s", path);
        free(p);
        free(out);
    }
}

/* python3's zlib decompresses the IDAT stream; its bytes must equal the
 * scanlines built here (filter 0 + row). */
static void png_python_zlib(void)
{
    if (!have("python3")) TST_SKIP("python3 not installed");
    int w = 123, h = 77, ch = 3;
    uint8_t *p = pattern(w, h, ch, 11), *out;
    size_t len;
    TST_EQ_INT(scn_png_encode(w, h, ch, p, &out, &len), 0);
    char png[700], rawp[700], script[700], cmd[2400];
    snprintf(png, sizeof png, "%s/py.png", tdir);
    snprintf(rawp, sizeof rawp, "%s/py.raw", tdir);
    snprintf(script, sizeof script, "%s/py.py", tdir);
    TST_EQ_INT(write_file(png, out, len), 0);
    FILE *f = fopen(script, "w");
    fputs("import sys, struct, zlib\n"
          "b = open(sys.argv[1], 'rb').read()\n"
          "o, z = 8, b''\n"
          "while o < len(b):\n"
          "    n, = struct.unpack('>I', b[o:o+4]); t = b[o+4:o+8]\n"
          "    if zlib.crc32(b[o+4:o+8+n]) & 0xffffffff != struct.unpack('>I', b[o+8+n:o+12+n])[0]:\n"
          "        sys.exit('crc')\n"
          "    if t == b'IDAT': z += b[o+8:o+8+n]\n"
          "    o += 12 + n\n"
          "open(sys.argv[2], 'wb').write(zlib.decompress(z))\n", f);
    fclose(f);
    snprintf(cmd, sizeof cmd, "python3 '%s' '%s' '%s'", script, png, rawp);
    TST_CHECK(system(cmd) == 0, "python3 zlib failed: %s", cmd);
    f = fopen(rawp, "rb");
    size_t row = (size_t)w * ch + 1;
    uint8_t *r = malloc(row * h + 1);
    size_t got = f ? fread(r, 1, row * h + 1, f) : 0;
    if (f) fclose(f);
    TST_EQ_INT(got, row * h);
    if (got == row * h)
        for (int y = 0; y < h; y++) {
            TST_EQ_INT(r[y * row], 0);
            TST_CHECK(!memcmp(r + y * row + 1, p + y * (row - 1), row - 1), "row %d differs", y);
        }
    free(r);
    free(p);
    free(out);
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
    TST_RUN(png_pngcheck);
    TST_RUN(png_python_zlib);
    TST_RUN(heat_map);
    TST_RUN(label_colours);
    tst_rmtree(tdir);
    rmdir(tdir);
    TST_EXIT();
}
