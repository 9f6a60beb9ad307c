/* scene_obj.c - Wavefront OBJ reader (see scene.h).
 *
 * Read: "v x y z" (extra numbers, w or a colour, allowed and dropped),
 * "vn x y z", "f" with corners "v", "v/vt", "v//vn" or "v/vt/vn"
 * (positive indices count from 1, negative ones back from the last
 * element read so far), polygons fanned into triangles (c0 ci ci+1).
 * "vt" lines are counted (face texture indices are range-checked) and,
 * like every other kind (o, g, s, usemtl, mtllib, l, p, ...), ignored and
 * counted in m->ignored. "#" starts a comment.
 *
 * A position referenced with several normals (or with and without one)
 * becomes several vertices: the mesh keeps one normal per vertex. A corner
 * without a normal gets the area-weighted normal of its position over all
 * faces of the file (scn_vertex_normals). A given normal is normalized;
 * a zero one falls back to the computed normal. Positions no face uses
 * are dropped. Region 0 everywhere.
 *
 * Errors "PATH:LINE: what" (or "PATH: what" for the whole file): an
 * index 0 or out of range, an unparsable or non-finite number, a
 * position or normal coordinate beyond SCN_OBJ_MAX_COORD, a v or vn
 * with fewer than 3 numbers, a face with fewer than 3 corners, a NUL or
 * control byte (binary data), fewer than 3 vertices or no face at all.
 * Files over 256 MiB are refused before reading (by size for regular
 * files, while reading for pipes), and so is a line over 1 MiB (reading
 * stops there: a stream without LF costs no more).
 */
#include "base/base_out.h"
#include "scene/scene_geom.h"
#include "base/base_line.h"
#include <errno.h>
#include <limits.h>
#include <stdarg.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define OBJ_MAX_BYTES ((off_t)256 << 20)
/* A line is a few dozen bytes; a face with thousands of corners fits. A
 * stream with no LF (/dev/zero, a binary file) stops here. */
#define OBJ_MAX_LINE (1 << 20)
#define NONE UINT32_MAX

/* A growing array of fixed-size elements. */
typedef struct { void *p; size_t n, cap, el; } vec;

static void *vec_push(vec *v)
{
    if (v->n == v->cap) {
        size_t nc = v->cap ? 2 * v->cap : 256;
        if (nc > SIZE_MAX / v->el) return NULL;
        void *np = realloc(v->p, nc * v->el);
        if (!np) return NULL;
        v->p = np;
        v->cap = nc;
    }
    return (char *)v->p + v->el * v->n++;
}

typedef struct {
    const char *path;
    size_t      line;
    char       *err;
    size_t      errlen;
} ctx;

static int fail(ctx *c, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static int fail(ctx *c, const char *fmt, ...)
{
    char what[256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(what, sizeof what, fmt, ap);
    va_end(ap);
    if (c->line) snprintf(c->err, c->errlen, "%s:%zu: %s", c->path, c->line, what);
    else snprintf(c->err, c->errlen, "%s: %s", c->path, what);
    return -1;
}

static int is_space(char ch)
{
    return ch == ' ' || ch == '\t' || ch == '\r' || ch == '\v' || ch == '\f';
}

/* Next whitespace-separated token of *s, NUL-terminated in place. */
static char *token(char **s)
{
    char *p = *s;
    while (is_space(*p)) p++;
    if (!*p) { *s = p; return NULL; }
    char *t = p;
    while (*p && !is_space(*p)) p++;
    if (*p) *p++ = 0;
    *s = p;
    return t;
}

/* The largest coordinate taken: the camera's transforms, the areas and
 * the normals multiply two coordinates' differences, which stay finite
 * below (2 x 1e150)^2; at 1e307 a perspective view overflowed to a frame
 * with nothing covered, reported as if the mesh were out of view. */
#define SCN_OBJ_MAX_COORD 1e150

/* "v"/"vn": at least 3 numbers (v: up to 7), all finite. */
static int numbers(ctx *c, char *s, const char *kw, int maxn, double out[3])
{
    int k = 0;
    char *t;
    while ((t = token(&s))) {
        if (k == maxn)
            return fail(c, "%s: more than %d numbers", kw, maxn);
        char *end;
        errno = 0;
        double x = strtod(t, &end);
        if (end == t || *end)
            return fail(c, "%s: '%.40s' is not a number", kw, t);
        if (!isfinite(x))
            return fail(c, "%s: '%.40s' is not a finite number", kw, t);
        if (k < 3 && fabs(x) > SCN_OBJ_MAX_COORD)
            return fail(c, "%s: '%.40s' is too large (coordinates up to 1e150: the camera's arithmetic "
                           "squares them)", kw, t);
        if (k < 3) out[k] = x;
        k++;
    }
    if (k < 3) return fail(c, "%s: needs 3 numbers, got %d", kw, k);
    return 0;
}

/* One index of a corner: count elements so far; 0-based result. */
static int index_of(ctx *c, const char *t, char **end, const char *what, size_t count, uint32_t *out)
{
    errno = 0;
    long long v = strtoll(t, end, 10);
    if (*end == t)
        return fail(c, "face: missing or bad %s index", what);
    if (v == 0)
        return fail(c, "face: %s index 0 (OBJ indices start at 1)", what);
    if (errno == ERANGE || (v > 0 && (unsigned long long)v > count) ||
        (v < 0 && (v == LLONG_MIN || (unsigned long long)-v > count)))
        return fail(c, "face: %s index %lld out of range (%zu so far)", what, v, count);
    *out = (uint32_t)(v > 0 ? v - 1 : (long long)count + v);
    return 0;
}

typedef struct { uint32_t v[3], n[3]; } otri;

static int face(ctx *c, char *s, size_t nv, size_t nvt, size_t nvn, vec *tris)
{
    uint32_t cv[3] = { 0 }, cn[3] = { 0 };
    int k = 0;
    char *t;
    while ((t = token(&s))) {
        uint32_t vi, ni = NONE, ti;
        char *e;
        if (index_of(c, t, &e, "vertex", nv, &vi)) return -1;
        if (*e == '/') {
            if (e[1] == '/') {                   /* v//vn */
                if (index_of(c, e + 2, &e, "normal", nvn, &ni)) return -1;
            } else {                             /* v/vt or v/vt/vn */
                if (index_of(c, e + 1, &e, "texture", nvt, &ti)) return -1;
                if (*e == '/' && index_of(c, e + 1, &e, "normal", nvn, &ni)) return -1;
            }
        }
        if (*e)
            return fail(c, "face: bad corner '%.40s' (v, v/vt, v//vn or v/vt/vn)", t);
        if (k < 2) {
            cv[k] = vi;
            cn[k] = ni;
        } else {
            cv[2] = vi;
            cn[2] = ni;
            otri *o = vec_push(tris);
            if (!o) base_out_of_memory();
            memcpy(o->v, cv, sizeof cv);
            memcpy(o->n, cn, sizeof cn);
            cv[1] = vi;                           /* fan: c0 ci ci+1 */
            cn[1] = ni;
        }
        k++;
    }
    if (k < 3) return fail(c, "face with %d corner%s: needs at least 3", k, k == 1 ? "" : "s");
    return 0;
}

/* Position/normal pairs seen so far: an open-addressing hash from the
 * pair to its output vertex, so that each corner costs O(1) however many
 * normals one position is used with. Vertices are numbered in the order
 * of their first corner. */
typedef struct { uint32_t v, n, out; } pair;

static size_t pair_hash(uint32_t v, uint32_t n, size_t mask)
{
    uint64_t h = ((uint64_t)v << 32 | n) * 0x9e3779b97f4a7c15ull;
    return (size_t)(h >> 32) & mask;
}

/* Build the mesh: split positions by normal index, compute missing normals. */
static int build(ctx *c, const vec *vp, const vec *vn, const vec *tris, scn_mesh *m)
{
    const double (*P)[3] = vp->p, (*N)[3] = vn->p;
    const otri *T = tris->p;
    size_t nt = tris->n, np = vp->n;
    size_t slots = 16;
    while (slots < 6 * nt) slots *= 2;  /* at most 3 nt pairs: load <= 1/2 */
    double (*auto_n)[3] = malloc((np ? np : 1) * sizeof *auto_n);
    uint32_t (*tv)[3] = malloc((nt ? nt : 1) * sizeof *tv);
    pair *tab = malloc(slots * sizeof *tab);
    pair *outs = malloc(3 * (nt ? nt : 1) * sizeof *outs);   /* [out]: its pair */
    int rc = -1;
    if (!auto_n || !tv || !tab || !outs) base_out_of_memory();
    for (size_t t = 0; t < nt; t++) memcpy(tv[t], T[t].v, sizeof tv[t]);
    scn_vertex_normals(P, np, (const uint32_t (*)[3])tv, nt, auto_n);
    for (size_t i = 0; i < slots; i++) tab[i].out = NONE;
    size_t nout = 0, mask = slots - 1;
    for (size_t t = 0; t < nt; t++)
        for (int k = 0; k < 3; k++) {
            uint32_t v = T[t].v[k], n = T[t].n[k];
            size_t h = pair_hash(v, n, mask);
            while (tab[h].out != NONE && (tab[h].v != v || tab[h].n != n)) h = (h + 1) & mask;
            if (tab[h].out == NONE) {
                tab[h] = (pair){ v, n, (uint32_t)nout };
                outs[nout++] = tab[h];
            }
            tv[t][k] = tab[h].out;
        }
    if (nout > UINT32_MAX || scn_mesh_alloc(m, nout, nt)) {   /* too many (out of memory exits) */
        c->line = 0;
        fail(c, "more than %u distinct vertex and normal pairs", (unsigned)UINT32_MAX);
        goto done;
    }
    for (size_t o = 0; o < nout; o++) {
        uint32_t v = outs[o].v, n = outs[o].n;
        memcpy(m->pos[o], P[v], sizeof m->pos[o]);
        if (n == NONE) {
            memcpy(m->nrm[o], auto_n[v], sizeof m->nrm[o]);
        } else {
            memcpy(m->nrm[o], N[n], sizeof m->nrm[o]);
            scn_normalize_or(m->nrm[o], auto_n[v]);
        }
    }
    memcpy(m->tri, tv, nt * sizeof *tv);
    rc = 0;
done:
    free(auto_n);
    free(tv);
    free(tab);
    free(outs);
    return rc;
}

int scn_mesh_obj(const char *path, scn_mesh *m, char *err, size_t errlen)
{
    memset(m, 0, sizeof *m);
    ctx c = { path, 0, err, errlen };
    int fd = open(path, O_RDONLY);
    if (fd < 0) return fail(&c, "cannot open: %s", strerror(errno));
    struct stat st;
    if (fstat(fd, &st)) {
        close(fd);
        return fail(&c, "cannot stat: %s", strerror(errno));
    }
    if (S_ISDIR(st.st_mode)) {
        close(fd);
        return fail(&c, "is a directory, not an OBJ file");
    }
    if (S_ISREG(st.st_mode) && st.st_size > OBJ_MAX_BYTES) {
        close(fd);
        return fail(&c, "file of %lld bytes: OBJ files over %lld MiB are refused",
                    (long long)st.st_size, (long long)(OBJ_MAX_BYTES >> 20));
    }
    FILE *f = fdopen(fd, "rb");
    if (!f) {
        close(fd);
        return fail(&c, "cannot open: %s", strerror(errno));
    }
    vec vp = { NULL, 0, 0, sizeof(double[3]) }, vn = { NULL, 0, 0, sizeof(double[3]) };
    vec tris = { NULL, 0, 0, sizeof(otri) };
    size_t nvt = 0, ignored = 0;
    long long total = 0;
    char *line = malloc(OBJ_MAX_LINE + 1);
    long len;
    int rc = -1;
    if (!line) base_out_of_memory();
    while ((len = base_line_read(f, line, OBJ_MAX_LINE)) >= 0 || len == BASE_LINE_LONG || len == BASE_LINE_NUL) {
        c.line++;
        if (len == BASE_LINE_LONG) {
            fail(&c, "line longer than %d bytes", OBJ_MAX_LINE);
            goto out;
        }
        if (len == BASE_LINE_NUL) {
            fail(&c, "binary data (byte 0x00): not an OBJ file");
            goto out;
        }
        total += len + 1;
        if (total > (long long)OBJ_MAX_BYTES) {
            fail(&c, "more than %lld MiB: OBJ files over that are refused",
                 (long long)(OBJ_MAX_BYTES >> 20));
            goto out;
        }
        for (long i = 0; i < len; i++) {
            unsigned char ch = (unsigned char)line[i];
            if (ch < 0x20 && !is_space((char)ch)) {
                fail(&c, "binary data (byte 0x%02x): not an OBJ file", ch);
                goto out;
            }
        }
        char *hash = strchr(line, '#');
        if (hash) *hash = 0;
        char *s = line, *kw = token(&s);
        if (!kw) continue;
        if (!strcmp(kw, "v") || !strcmp(kw, "vn")) {
            int isv = kw[1] == 0;
            double p[3];
            if (numbers(&c, s, kw, isv ? 7 : 3, p)) goto out;
            vec *dst = isv ? &vp : &vn;
            if (dst->n >= UINT32_MAX - 1) {
                fail(&c, "too many %s lines", kw);
                goto out;
            }
            double *d = vec_push(dst);
            if (!d) base_out_of_memory();
            memcpy(d, p, sizeof p);
        } else if (!strcmp(kw, "f")) {
            if (face(&c, s, vp.n, nvt, vn.n, &tris)) goto out;
        } else {
            if (!strcmp(kw, "vt")) nvt++;
            ignored++;
        }
    }
    if (len == BASE_LINE_ERR) {
        c.line = 0;
        fail(&c, "read error: %s", strerror(errno ? errno : EIO));
        goto out;
    }
    c.line = 0;
    if (vp.n < 3) {
        fail(&c, "too few vertices (%zu): a mesh needs at least 3", vp.n);
        goto out;
    }
    if (!tris.n) {
        fail(&c, "no faces: nothing to draw");
        goto out;
    }
    if (tris.n > INT32_MAX) {
        fail(&c, "too many triangles (%zu)", tris.n);
        goto out;
    }
    if (build(&c, &vp, &vn, &tris, m)) goto out;
    m->ignored = ignored;
    rc = 0;
out:
    free(line);
    fclose(f);
    free(vp.p);
    free(vn.p);
    free(tris.p);
    return rc;
}
