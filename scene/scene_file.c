/* scene_file.c - the scene description format, version 1.
 *
 * A scene file is text, one setting per line: a key, then its values,
 * separated by blanks or commas. '#' at the start of a line (after
 * blanks), or after a blank, starts a comment to the end of the line; blank
 * lines are skipped. The first line that is not blank or a comment must be
 *
 *     shadesim-scene 1
 *
 * Every key has a default (the built-in "face" scene); a file says only
 * what differs. A key given twice: the last wins, except the repeatable
 * ones (light, heldout-light, fmt), marked *. Numbers are decimal (C
 * syntax, e.g. 0.35, -1e-3); NaN and infinities are refused.
 *
 * key            values                              default
 * -------------  ----------------------------------  ----------------------------
 * mesh           face|sphere|torus|PATH.obj          face
 *                (the rest of the line; a relative PATH is relative to the
 *                scene file's folder; a built-in name wins over a file of
 *                that name: write ./face to mean the file)
 * detail         N (1..8): tessellation of built-ins 1
 * resolution     WxH (each 1..4096)                  512x512
 * camera         ortho|perspective                   ortho
 * eye            X Y Z                               0 0 5
 * target         X Y Z (not equal to eye)            0 0 0
 * up             X Y Z (not zero)                    0 1 0
 * fov            DEG, 0 < DEG < 180 (perspective:    30
 *                vertical field of view)
 * ortho-height   H > 0 (ortho: world height shown)   2.1
 * light *        none | directional X Y Z [I] |      directional -0.48 0.6 0.64 1
 *                point X Y Z [I]; I >= 0, default 1  (upper left front)
 *                (directional: direction towards the light, normalized when
 *                read; point: position. The first light line of a file
 *                replaces the default lights, later ones add one each, at
 *                most 4; from --set, light adds one. none: no lights.)
 * heldout-eye    auto | X Y Z                        auto: eye turned 20 degrees
 *                                                    about up through target
 * heldout-target auto | X Y Z                        auto: target
 * heldout-light* auto | none | directional|point     auto: each light turned 70
 *                X Y Z [I]                           degrees about up (through
 *                                                    target for point lights)
 *                (the held-out view is the one a format search does not see;
 *                its camera kind, up, fov and ortho-height are the view's.
 *                The first explicit heldout-light replaces the derived ones.)
 * ambient        A in [0, 1]                         0.05
 * kd             K in [0, 1] (diffuse)               0.6
 * ks             K in [0, 1] (specular)              0.35
 * shininess      N in [0, 10000] (phong, blinn)      24
 * specular       phong|blinn|cook|ward               blinn
 * distribution   beckmann|d4|d8|d16 (cook)           beckmann
 * ward-form      exact|poly16 (ward)                 exact
 * roughness      M in [0.01, 1] (cook)               0.3
 * ward-alpha     A in [0.01, 1] (ward)               0.3
 * fresnel        none|schlick|mschlick (cook)        none
 * fresnel-n      N in [1, 10000]                     2
 * policy         linear|quadratic|cubic-n1|cubic-n2| cubic-n1
 *                adaptive-region|adaptive-auto
 * region-degree  R D: region R (0..15) gets degree   2 for regions 2, 4, 7
 *                D (2 or 3) (adaptive-region)        (forehead, cheeks, chin),
 *                                                    3 for the others
 * auto-threshold X >= 0 (adaptive-auto)              0.01
 * auto-nodes     n1|n2 (adaptive-auto cubic)         n1
 * L              N (2..64): pixels per interval      8
 * terms          N (1..20): /3 network terms         3
 * series         paper|quarter (/3 network)          paper
 * width          W (4..64): default-format width     16
 * fmt *          none | NAME=sI.F|uI.F ... (signal   none
 *                formats in order; "all" for every signal; none clears;
 *                a format may end in :ROUND and/or :OVERFLOW, its own modes)
 * round          trunc|half-up|even                  trunc
 * overflow       wrap|sat                            wrap
 * schedule       paper|mac|pipe                      paper
 * cost           OP=W ... (OP add mul div sqrt pow;  add=1 mul=1 div=4 sqrt=4 pow=8
 *                W in [0, 1e6])
 *
 * Why these costs: they weigh the operations the reference and the method
 * need per pixel roughly as a floating-point unit's throughput does on
 * current processors: add and multiply are pipelined (one result a clock),
 * divide and square root are partly iterative (several clocks a result, ~4x),
 * and pow is a library call of a logarithm, an exponential and a few
 * multiply-adds (~8x). Change them with "cost" to weigh other hardware.
 *
 * The derived values (held-out eye, target, lights marked auto) follow the
 * view: setting eye after heldout-eye auto still moves the held-out eye.
 * Coordinates (eye, target, up, light) are world units within +-1e6; the
 * built-in meshes are about unit size around the origin, +y up, facing +z.
 * Lines may end in CR LF.
 *
 * Built-in scenes (scn_desc_builtin): "face" is the table above; "sphere"
 * is the same with mesh sphere and ortho-height 2.4 (radius 1 and a
 * margin); "torus" is the same with mesh torus, camera perspective and
 * fov 28 (2.5 units shown at the distance 5 of the eye).
 *
 * Errors: "PATH:LINE: what" for a bad line (unknown key with the closest
 * key suggested, wrong count of values, not a number, out of range, bad
 * name, too many lights, a line over 4095 bytes, a NUL byte); from
 * scn_desc_set "KEY: what". The description is only changed on success.
 */
#include "scene/scene.h"
#include "sim/sim_fixed.h"      /* the sim_round / sim_ovf values only */
#include "base/base_join.h"
#include "base/base_line.h"
#include "base/base_num.h"
#include "base/base_near.h"
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define LINE_MAX_BYTES 4095
#define MAX_TOK 40
#define HELD_EYE_DEG   20.0
#define HELD_LIGHT_DEG 70.0

const char *const scn_op_name[SCN_OP__COUNT] = { "add", "mul", "div", "sqrt", "pow" };

static const char *const policy_names[SCN_POL__COUNT] = {
    "linear", "quadratic", "cubic-n1", "cubic-n2", "adaptive-region", "adaptive-auto" };
static const char *const spec_names[SCN_SPEC__COUNT] = { "phong", "blinn", "cook", "ward" };
static const char *const fresnel_names[] = { "none", "schlick", "mschlick", NULL };
static const char *const round_names[] = { "trunc", "half-up", "even", NULL };
static const char *const ovf_names[] = { "wrap", "sat", NULL };
static const char *const schedule_names[] = { "paper", "mac", "pipe", NULL };
static const char *const series_names[] = { "paper", "quarter", NULL };
static const char *const camera_names[] = { "ortho", "perspective", NULL };

const char *const scn_desc_builtin_names[] = { "face", "sphere", "torus", NULL };

const char *scn_policy_name(scn_policy p)
{
    return (unsigned)p < SCN_POL__COUNT ? policy_names[p] : "?";
}

/* ---------------------------------------------------------- defaults */

void scn_desc_default(scn_desc *d)
{
    memset(d, 0, sizeof *d);
    d->version = 1;
    strcpy(d->mesh, "face");
    d->detail = 1;
    d->width = d->height = 512;
    scn_camera *c = &d->view.cam;
    c->perspective = 0;
    c->eye[2] = 5.0;
    c->up[1] = 1.0;
    c->fov_deg = 30.0;
    c->ortho_height = 2.1;      /* the head is 1.9 tall: a small margin */
    d->view.nlights = 1;
    /* Upper left front, a unit vector exactly: (-12, 15, 16) / 25. */
    d->view.light[0] = (scn_light){ 0, { -0.48, 0.6, 0.64 }, 1.0 };
    d->mat = (scn_material){ .ambient = 0.05, .kd = 0.6, .ks = 0.35, .shininess = 24.0,
                             .spec = SCN_SPEC_BLINN, .dg = 0, .m = 0.3, .alpha = 0.3,
                             .fresnel = SCN_FRESNEL_NONE, .fresnel_n = 2.0 };
    d->policy = SCN_POL_CUBIC_N1;
    for (int r = 0; r < SCN_MAX_REGIONS; r++) d->region_deg[r] = 3;
    d->region_deg[2] = d->region_deg[4] = d->region_deg[7] = 2;
    d->auto_cubic_nodes = 1;
    d->auto_threshold = 0.01;
    d->L = 8;
    d->terms = 3;
    d->series = 0;
    d->fmt_width = 16;
    d->nfmt = 0;
    d->rnd = SIM_RND_TRUNC;
    d->ovf = SIM_OVF_WRAP;
    strcpy(d->schedule, "paper");
    d->cost[SCN_OP_ADD] = 1.0;
    d->cost[SCN_OP_MUL] = 1.0;
    d->cost[SCN_OP_DIV] = 4.0;
    d->cost[SCN_OP_SQRT] = 4.0;
    d->cost[SCN_OP_POW] = 8.0;
    d->cook_dg = d->ward_dg = 0;
    d->heldout_given = 0;
    scn_desc_sync(d);
}

int scn_desc_builtin(const char *name, scn_desc *d)
{
    if (!name) return -1;
    scn_desc t;
    scn_desc_default(&t);
    if (!strcmp(name, "face")) {
        /* the defaults */
    } else if (!strcmp(name, "sphere")) {
        strcpy(t.mesh, "sphere");
        t.view.cam.ortho_height = 2.4;          /* radius 1 with a margin */
    } else if (!strcmp(name, "torus")) {
        /* Radius 1 (0.7 + 0.3) around the origin; a perspective view, so
         * the built-ins exercise both cameras. At distance 5, 28 degrees
         * show 2.49 units vertically. */
        strcpy(t.mesh, "torus");
        t.view.cam.perspective = 1;
        t.view.cam.fov_deg = 28.0;
    } else {
        return -1;
    }
    scn_desc_sync(&t);
    *d = t;
    return 0;
}

/* ------------------------------------------------ the held-out view */

/* v rotated by deg about the unit axis k (Rodrigues). */
static void rotate(const double v[3], const double k[3], double deg, double out[3])
{
    double a = deg * M_PI / 180.0, c = cos(a), s = sin(a);
    double kv = k[0] * v[0] + k[1] * v[1] + k[2] * v[2];
    double x[3] = { k[1] * v[2] - k[2] * v[1], k[2] * v[0] - k[0] * v[2],
                    k[0] * v[1] - k[1] * v[0] };
    for (int i = 0; i < 3; i++) out[i] = v[i] * c + x[i] * s + k[i] * kv * (1.0 - c);
}

void scn_desc_sync(scn_desc *d)
{
    const scn_camera *c = &d->view.cam;
    scn_camera *h = &d->heldout.cam;
    h->perspective = c->perspective;
    memcpy(h->up, c->up, sizeof h->up);
    h->fov_deg = c->fov_deg;
    h->ortho_height = c->ortho_height;
    double k[3] = { c->up[0], c->up[1], c->up[2] };
    double len = sqrt(k[0] * k[0] + k[1] * k[1] + k[2] * k[2]);
    if (len > 0.0) { k[0] /= len; k[1] /= len; k[2] /= len; }
    else { k[0] = 0.0; k[1] = 1.0; k[2] = 0.0; }
    if (!(d->heldout_given & SCN_HELD_TARGET)) memcpy(h->target, c->target, sizeof h->target);
    if (!(d->heldout_given & SCN_HELD_EYE)) {
        /* Turned about the vertical axis through the view's target. */
        double rel[3] = { c->eye[0] - c->target[0], c->eye[1] - c->target[1],
                          c->eye[2] - c->target[2] }, r[3];
        rotate(rel, k, HELD_EYE_DEG, r);
        for (int i = 0; i < 3; i++) h->eye[i] = c->target[i] + r[i];
    }
    if (!(d->heldout_given & SCN_HELD_LIGHT)) {
        d->heldout.nlights = d->view.nlights;
        for (int j = 0; j < d->view.nlights && j < SCN_MAX_LIGHTS; j++) {
            const scn_light *l = &d->view.light[j];
            scn_light *o = &d->heldout.light[j];
            *o = *l;
            if (l->point) {
                double rel[3] = { l->v[0] - c->target[0], l->v[1] - c->target[1],
                                  l->v[2] - c->target[2] }, r[3];
                rotate(rel, k, HELD_LIGHT_DEG, r);
                for (int i = 0; i < 3; i++) o->v[i] = c->target[i] + r[i];
            } else {
                rotate(l->v, k, HELD_LIGHT_DEG, o->v);
            }
        }
    }
}

/* ---------------------------------------------------- value parsing */

typedef struct ctx {
    int         from_file;          /* 1: scn_desc_read (first light line replaces) */
    int         light_seen;         /* a light line was read from this file */
    const char *dir;                /* scene file's folder (dirlen bytes), NULL: none */
    size_t      dirlen;             /* 0 with dir set: the root, "/" */
    int         line;               /* the line being applied (SCN_LINE_SET: --set) */
} ctx;

/* Error text without the "PATH:LINE: " / "KEY: " prefix. */
static int fail(char *err, size_t errlen, const char *fmt, ...)
{
    if (err && errlen) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err, errlen, fmt, ap);
        va_end(ap);
    }
    return -1;
}

/* A token shown in a message: printable ASCII only, at most 40 bytes. */
static const char *shown(const char *s, char buf[48])
{
    size_t i = 0;
    for (; s[i] && i < 40; i++) buf[i] = isprint((unsigned char)s[i]) ? s[i] : '?';
    if (s[i]) { buf[i++] = '.'; buf[i++] = '.'; buf[i++] = '.'; }
    buf[i] = 0;
    return buf;
}

static int num(const char *key, const char *s, double lo, double hi, double *out,
               char *err, size_t errlen)
{
    char b[48];
    double v;
    if (base_num_real(s, 1, &v))
        return fail(err, errlen, "%s: \"%s\" is not a finite number (decimal)", key, shown(s, b));
    if (v < lo || v > hi || (*s == '-' && lo >= 0))     /* -0 too */
        return fail(err, errlen, "%s: %s is out of range [%g, %g]", key, shown(s, b), lo, hi);
    *out = v;
    return 0;
}

static int inum(const char *key, const char *s, long lo, long hi, int *out,
                char *err, size_t errlen)
{
    char b[48];
    long long v;
    if (base_num_whole(s, 1, &v))
        return fail(err, errlen, "%s: \"%s\" is not an integer", key, shown(s, b));
    if (v < lo || v > hi || (*s == '-' && lo >= 0))     /* -0 too */
        return fail(err, errlen, "%s: %s is out of range %ld..%ld", key, shown(s, b), lo, hi);
    *out = (int)v;
    return 0;
}

/* Index of s in a NULL-terminated list, or -1 with a message. */
static int pick(const char *key, const char *s, const char *const *names, int n,
                char *err, size_t errlen)
{
    for (int i = 0; (n < 0 || i < n) && names[i]; i++)
        if (!strcmp(s, names[i])) return i;
    char b[48], list[160] = "";
    for (int i = 0; (n < 0 || i < n) && names[i]; i++) base_join_add(list, sizeof list, ", ", names[i]);
    return fail(err, errlen, "%s: \"%s\" is not one of %s", key, shown(s, b), list);
}

static int count(const char *key, int ntok, int lo, int hi, const char *what,
                 char *err, size_t errlen)
{
    if (ntok >= lo && ntok <= hi) return 0;
    if (lo == hi)
        return fail(err, errlen, "%s: takes %d value%s (%s), got %d", key, lo,
                    lo == 1 ? "" : "s", what, ntok);
    return fail(err, errlen, "%s: takes %d to %d values (%s), got %d", key, lo, hi, what, ntok);
}

static int vec3(const char *key, char **t, double v[3], char *err, size_t errlen)
{
    double r[3];
    for (int i = 0; i < 3; i++)
        if (num(key, t[i], -1e6, 1e6, &r[i], err, errlen)) return -1;
    memcpy(v, r, sizeof r);
    return 0;
}

/* "directional X Y Z [I]" / "point X Y Z [I]" into l. */
static int light_of(const char *key, char **t, int n, scn_light *l, char *err, size_t errlen)
{
    if (count(key, n, 4, 5, "directional|point X Y Z [intensity]", err, errlen)) return -1;
    int k = pick(key, t[0], (const char *const[]){ "directional", "point", NULL }, -1,
                 err, errlen);
    if (k < 0) return -1;
    scn_light r = { k, { 0, 0, 0 }, 1.0 };
    if (vec3(key, t + 1, r.v, err, errlen)) return -1;
    if (n == 5 && num(key, t[4], 0.0, 1e6, &r.intensity, err, errlen)) return -1;
    if (!k) {
        double len = sqrt(r.v[0] * r.v[0] + r.v[1] * r.v[1] + r.v[2] * r.v[2]);
        if (!(len > 0.0)) return fail(err, errlen, "%s: a direction of length 0", key);
        /* A direction already of unit length (as written back) stays
         * bit for bit what it was: the round trip is exact. */
        if (fabs(len - 1.0) > 1e-12)
            for (int i = 0; i < 3; i++) r.v[i] /= len;
    }
    *l = r;
    return 0;
}

/* The modes after a format, ":ROUND" and/or ":OVERFLOW" in either order,
 * each at most once (the testbench's parser reads them; this layer only
 * checks the text, to report the file's line). p at the first ':' or the
 * end; 0, or -1 with the reason in why. */
static int fmt_modes_ok(const char *p, char *why, size_t n)
{
    static const char *const rn[] = { "trunc", "half-up", "even" }, *on[] = { "wrap", "sat" };
    int has_r = 0, has_o = 0;
    while (*p == ':') {
        const char *m = p + 1;
        size_t len = strcspn(m, ":");
        int r = 0, o = 0;
        for (int i = 0; i < 3; i++) r |= strlen(rn[i]) == len && !strncmp(m, rn[i], len);
        for (int i = 0; i < 2; i++) o |= strlen(on[i]) == len && !strncmp(m, on[i], len);
        if (!len) { snprintf(why, n, "empty mode after ':'"); return -1; }
        if (!r && !o) { snprintf(why, n, "unknown mode (rounding: trunc, half-up, even; overflow: wrap, sat)"); return -1; }
        if ((r && has_r) || (o && has_o)) { snprintf(why, n, "%s mode given twice", r ? "rounding" : "overflow"); return -1; }
        has_r |= r;
        has_o |= o;
        p = m + len;
    }
    return 0;
}

/* "NAME=sI.F[:ROUND][:OVERFLOW]" with NAME of [a-z0-9_] (signal names are
 * lower case). */
static int fmt_ok(const char *s, char *err, size_t errlen)
{
    char b[48], why[100];
    const char *p = s;
    while (*p && (islower((unsigned char)*p) || isdigit((unsigned char)*p) || *p == '_')) p++;
    int bad = p == s || *p != '=' || (p[1] != 's' && p[1] != 'u');
    long ib = -1, fb = -1;
    if (!bad) {
        char *e;
        p += 2;
        if (!isdigit((unsigned char)*p)) bad = 1;
        else {
            ib = strtol(p, &e, 10);
            if (*e != '.' || !isdigit((unsigned char)e[1])) bad = 1;
            else {
                fb = strtol(e + 1, &e, 10);
                if (*e && *e != ':') bad = 1;
                else if (fmt_modes_ok(e, why, sizeof why))
                    return fail(err, errlen, "fmt: \"%s\": %s", shown(s, b), why);
            }
        }
    }
    if (bad)
        return fail(err, errlen, "fmt: \"%s\" is not NAME=sI.F or NAME=uI.F", shown(s, b));
    long w = ib + fb, maxw = s[strcspn(s, "=") + 1] == 's' ? 64 : 63;
    if (ib > 64 || fb > 64 || w < 1 || w > maxw)
        return fail(err, errlen, "fmt: \"%s\": width I+F must be 1..%ld", shown(s, b), maxw);
    if (strlen(s) >= sizeof ((scn_desc *)0)->fmt[0])
        return fail(err, errlen, "fmt: \"%s\" is too long", shown(s, b));
    return 0;
}

/* ------------------------------------------------------- the keys */

enum {
    K_MESH, K_DETAIL, K_RES, K_CAMERA, K_EYE, K_TARGET, K_UP, K_FOV, K_OHEIGHT, K_LIGHT,
    K_HEYE, K_HTARGET, K_HLIGHT, K_AMBIENT, K_KD, K_KS, K_SHININESS, K_SPECULAR, K_DIST,
    K_WARDFORM, K_ROUGH, K_WALPHA, K_FRESNEL, K_FRESN, K_POLICY, K_REGDEG, K_ATHRESH,
    K_ANODES, K_L, K_TERMS, K_SERIES, K_WIDTH, K_FMT, K_ROUND, K_OVERFLOW, K_SCHEDULE,
    K_COST, K__COUNT
};

const char *const scn_desc_keys[K__COUNT + 1] = {
    "mesh", "detail", "resolution", "camera", "eye", "target", "up", "fov", "ortho-height",
    "light", "heldout-eye", "heldout-target", "heldout-light", "ambient", "kd", "ks",
    "shininess", "specular", "distribution", "ward-form", "roughness", "ward-alpha",
    "fresnel", "fresnel-n", "policy", "region-degree", "auto-threshold", "auto-nodes", "L",
    "terms", "series", "width", "fmt", "round", "overflow", "schedule", "cost", NULL };

static int unknown_key(const char *key, char *err, size_t errlen)
{
    char b[48];
    const char *near = base_near(key, scn_desc_keys, K__COUNT);
    if (near) return fail(err, errlen, "unknown key \"%s\" (did you mean \"%s\"?)", shown(key, b), near);
    return fail(err, errlen, "unknown key \"%s\"", shown(key, b));
}

/* mat.dg from the model and the two remembered forms. */
static void set_dg(scn_desc *d)
{
    d->mat.dg = d->mat.spec == SCN_SPEC_COOK ? d->cook_dg
              : d->mat.spec == SCN_SPEC_WARD ? d->ward_dg : 0;
}

/* Apply one key with its value tokens t[0..n-1] (rest: the value text as
 * written, for mesh). d is a scratch copy: it may be left half-changed on
 * error, the callers discard it then. */
static int apply(scn_desc *d, ctx *cx, const char *key, char **t, int n, const char *rest,
                 char *err, size_t errlen)
{
    int k;
    for (k = 0; k < K__COUNT; k++)
        if (!strcmp(key, scn_desc_keys[k])) break;
    if (k == K__COUNT) return unknown_key(key, err, errlen);
    d->key_line[k] = cx->line;
    scn_camera *cam = &d->view.cam;
    int i;
    double x;
    switch (k) {
    case K_MESH: {
        if (!rest || !*rest) return fail(err, errlen, "mesh: takes a built-in name or an OBJ path");
        int builtin = 0;
        for (i = 0; scn_desc_builtin_names[i]; i++)
            if (!strcmp(rest, scn_desc_builtin_names[i])) builtin = 1;
        size_t rl = strlen(rest);
        if (builtin || rest[0] == '/' || !cx->dir) {
            if (rl >= sizeof d->mesh) return fail(err, errlen, "mesh: path too long");
            memcpy(d->mesh, rest, rl + 1);
        } else {
            if (cx->dirlen + 1 + rl >= sizeof d->mesh) return fail(err, errlen, "mesh: path too long");
            memcpy(d->mesh, cx->dir, cx->dirlen);
            d->mesh[cx->dirlen] = '/';
            memcpy(d->mesh + cx->dirlen + 1, rest, rl + 1);
        }
        return 0;
    }
    case K_DETAIL:
        if (count(key, n, 1, 1, "N", err, errlen)) return -1;
        return inum(key, t[0], 1, 8, &d->detail, err, errlen);
    case K_RES: {
        if (count(key, n, 1, 1, "WxH", err, errlen)) return -1;
        char b[48];
        const char *s = t[0];
        const char *xp = strchr(s, 'x');
        if (!xp || xp == s || !xp[1] || xp - s > 20)
            return fail(err, errlen, "resolution: \"%s\" is not WxH", shown(s, b));
        char w[24];
        memcpy(w, s, (size_t)(xp - s));
        w[xp - s] = 0;
        int wv, hv;
        if (inum("resolution width", w, 1, 4096, &wv, err, errlen) ||
            inum("resolution height", xp + 1, 1, 4096, &hv, err, errlen)) return -1;
        d->width = wv;
        d->height = hv;
        return 0;
    }
    case K_CAMERA:
        if (count(key, n, 1, 1, "ortho|perspective", err, errlen)) return -1;
        if ((i = pick(key, t[0], camera_names, -1, err, errlen)) < 0) return -1;
        cam->perspective = i;
        return 0;
    case K_EYE:
    case K_TARGET:
    case K_UP: {
        if (count(key, n, 3, 3, "X Y Z", err, errlen)) return -1;
        double v[3];
        if (vec3(key, t, v, err, errlen)) return -1;
        if (k == K_UP && v[0] == 0.0 && v[1] == 0.0 && v[2] == 0.0)
            return fail(err, errlen, "up: a direction of length 0");
        memcpy(k == K_EYE ? cam->eye : k == K_TARGET ? cam->target : cam->up, v, sizeof v);
        return 0;
    }
    case K_FOV:
        if (count(key, n, 1, 1, "degrees", err, errlen)) return -1;
        if (num(key, t[0], 0.0, 180.0, &x, err, errlen)) return -1;
        if (x <= 0.0 || x >= 180.0)
            return fail(err, errlen, "fov: %g is out of range (0 < fov < 180)", x);
        cam->fov_deg = x;
        return 0;
    case K_OHEIGHT:
        if (count(key, n, 1, 1, "H", err, errlen)) return -1;
        if (num(key, t[0], 0.0, 1e6, &x, err, errlen)) return -1;
        if (x <= 0.0) return fail(err, errlen, "ortho-height: must be > 0");
        cam->ortho_height = x;
        return 0;
    case K_LIGHT:
    case K_HLIGHT: {
        scn_view *v = k == K_LIGHT ? &d->view : &d->heldout;
        if (n == 1 && !strcmp(t[0], "none")) {
            v->nlights = 0;
            if (k == K_LIGHT) cx->light_seen = 1;
            else d->heldout_given |= SCN_HELD_LIGHT;
            return 0;
        }
        if (k == K_HLIGHT && n == 1 && !strcmp(t[0], "auto")) {
            d->heldout_given &= ~SCN_HELD_LIGHT;
            return 0;
        }
        scn_light l;
        if (light_of(key, t, n, &l, err, errlen)) return -1;
        if (k == K_LIGHT) {
            if (cx->from_file && !cx->light_seen) v->nlights = 0;
            cx->light_seen = 1;
        } else if (!(d->heldout_given & SCN_HELD_LIGHT)) {
            v->nlights = 0;
            d->heldout_given |= SCN_HELD_LIGHT;
        }
        if (v->nlights >= SCN_MAX_LIGHTS)
            return fail(err, errlen, "%s: too many lights (at most %d)", key, SCN_MAX_LIGHTS);
        v->light[v->nlights++] = l;
        return 0;
    }
    case K_HEYE:
    case K_HTARGET: {
        unsigned bit = k == K_HEYE ? SCN_HELD_EYE : SCN_HELD_TARGET;
        if (n == 1 && !strcmp(t[0], "auto")) { d->heldout_given &= ~bit; return 0; }
        if (count(key, n, 3, 3, "auto or X Y Z", err, errlen)) return -1;
        if (vec3(key, t, k == K_HEYE ? d->heldout.cam.eye : d->heldout.cam.target,
                 err, errlen)) return -1;
        d->heldout_given |= bit;
        return 0;
    }
    case K_AMBIENT:
    case K_KD:
    case K_KS:
        if (count(key, n, 1, 1, "a number in [0, 1]", err, errlen)) return -1;
        return num(key, t[0], 0.0, 1.0,
                   k == K_AMBIENT ? &d->mat.ambient : k == K_KD ? &d->mat.kd : &d->mat.ks,
                   err, errlen);
    case K_SHININESS:
        if (count(key, n, 1, 1, "N", err, errlen)) return -1;
        return num(key, t[0], 0.0, 10000.0, &d->mat.shininess, err, errlen);
    case K_SPECULAR:
        if (count(key, n, 1, 1, "phong|blinn|cook|ward", err, errlen)) return -1;
        if ((i = pick(key, t[0], spec_names, SCN_SPEC__COUNT, err, errlen)) < 0) return -1;
        d->mat.spec = (scn_spec_model)i;
        set_dg(d);
        return 0;
    case K_DIST: {
        static const char *const nm[] = { "beckmann", "d4", "d8", "d16", NULL };
        static const int g[] = { 0, 4, 8, 16 };
        if (count(key, n, 1, 1, "beckmann|d4|d8|d16", err, errlen)) return -1;
        if ((i = pick(key, t[0], nm, -1, err, errlen)) < 0) return -1;
        d->cook_dg = g[i];
        set_dg(d);
        return 0;
    }
    case K_WARDFORM:
        if (count(key, n, 1, 1, "exact|poly16", err, errlen)) return -1;
        if ((i = pick(key, t[0], (const char *const[]){ "exact", "poly16", NULL }, -1,
                      err, errlen)) < 0) return -1;
        d->ward_dg = i ? 16 : 0;
        set_dg(d);
        return 0;
    case K_ROUGH:
    case K_WALPHA:
        if (count(key, n, 1, 1, "a number in [0.01, 1]", err, errlen)) return -1;
        return num(key, t[0], 0.01, 1.0, k == K_ROUGH ? &d->mat.m : &d->mat.alpha, err, errlen);
    case K_FRESNEL:
        if (count(key, n, 1, 1, "none|schlick|mschlick", err, errlen)) return -1;
        if ((i = pick(key, t[0], fresnel_names, -1, err, errlen)) < 0) return -1;
        d->mat.fresnel = (scn_fresnel)i;
        return 0;
    case K_FRESN:
        if (count(key, n, 1, 1, "N", err, errlen)) return -1;
        return num(key, t[0], 1.0, 10000.0, &d->mat.fresnel_n, err, errlen);
    case K_POLICY:
        if (count(key, n, 1, 1, "a policy name", err, errlen)) return -1;
        if ((i = pick(key, t[0], policy_names, SCN_POL__COUNT, err, errlen)) < 0) return -1;
        d->policy = (scn_policy)i;
        return 0;
    case K_REGDEG: {
        if (count(key, n, 2, 2, "REGION DEGREE", err, errlen)) return -1;
        int r, g;
        if (inum("region-degree region", t[0], 0, SCN_MAX_REGIONS - 1, &r, err, errlen) ||
            inum("region-degree degree", t[1], 2, 3, &g, err, errlen)) return -1;
        d->region_deg[r] = (uint8_t)g;
        return 0;
    }
    case K_ATHRESH:
        if (count(key, n, 1, 1, "X", err, errlen)) return -1;
        return num(key, t[0], 0.0, 1e6, &d->auto_threshold, err, errlen);
    case K_ANODES:
        if (count(key, n, 1, 1, "n1|n2", err, errlen)) return -1;
        if ((i = pick(key, t[0], (const char *const[]){ "n1", "n2", NULL }, -1,
                      err, errlen)) < 0) return -1;
        d->auto_cubic_nodes = i + 1;
        return 0;
    case K_L:
        if (count(key, n, 1, 1, "N", err, errlen)) return -1;
        return inum(key, t[0], 2, 64, &d->L, err, errlen);
    case K_TERMS:
        if (count(key, n, 1, 1, "N", err, errlen)) return -1;
        return inum(key, t[0], 1, 20, &d->terms, err, errlen);
    case K_SERIES:
        if (count(key, n, 1, 1, "paper|quarter", err, errlen)) return -1;
        if ((i = pick(key, t[0], series_names, -1, err, errlen)) < 0) return -1;
        d->series = i;
        return 0;
    case K_WIDTH:
        if (count(key, n, 1, 1, "W", err, errlen)) return -1;
        return inum(key, t[0], 4, 64, &d->fmt_width, err, errlen);
    case K_FMT:
        if (n == 1 && !strcmp(t[0], "none")) { d->nfmt = 0; return 0; }
        if (n < 1) return fail(err, errlen, "fmt: takes none or NAME=sI.F values, got none");
        for (i = 0; i < n; i++) {
            if (fmt_ok(t[i], err, errlen)) return -1;
            if (d->nfmt >= SCN_MAX_FMT)
                return fail(err, errlen, "fmt: too many formats (at most %d)", SCN_MAX_FMT);
            strcpy(d->fmt[d->nfmt++], t[i]);
        }
        return 0;
    case K_ROUND:
        if (count(key, n, 1, 1, "trunc|half-up|even", err, errlen)) return -1;
        if ((i = pick(key, t[0], round_names, -1, err, errlen)) < 0) return -1;
        d->rnd = i;
        return 0;
    case K_OVERFLOW:
        if (count(key, n, 1, 1, "wrap|sat", err, errlen)) return -1;
        if ((i = pick(key, t[0], ovf_names, -1, err, errlen)) < 0) return -1;
        d->ovf = i;
        return 0;
    case K_SCHEDULE:
        if (count(key, n, 1, 1, "paper|mac|pipe", err, errlen)) return -1;
        if ((i = pick(key, t[0], schedule_names, -1, err, errlen)) < 0) return -1;
        strcpy(d->schedule, schedule_names[i]);
        return 0;
    case K_COST:
        if (n < 1) return fail(err, errlen, "cost: takes OP=W values (OP add mul div sqrt pow), got none");
        for (i = 0; i < n; i++) {
            char b[48], name[8];
            const char *eq = strchr(t[i], '=');
            size_t nl = eq ? (size_t)(eq - t[i]) : 0;
            if (!eq || nl == 0 || nl >= sizeof name)
                return fail(err, errlen, "cost: \"%s\" is not OP=W", shown(t[i], b));
            memcpy(name, t[i], nl);
            name[nl] = 0;
            int op = pick("cost", name, scn_op_name, SCN_OP__COUNT, err, errlen);
            if (op < 0) return -1;
            if (num("cost", eq + 1, 0.0, 1e6, &d->cost[op], err, errlen)) return -1;
        }
        return 0;
    }
    return unknown_key(key, err, errlen);
}

/* Split s (modified in place) at blanks and commas. -1 if more than max. */
static int split(char *s, char **t, int max)
{
    int n = 0;
    for (;;) {
        while (*s == ' ' || *s == '\t' || *s == ',' || *s == '\r' || *s == '\v' || *s == '\f') s++;
        if (!*s) return n;
        if (n == max) return -1;
        t[n++] = s;
        while (*s && !(*s == ' ' || *s == '\t' || *s == ',' || *s == '\r' || *s == '\v' || *s == '\f')) s++;
        if (*s) *s++ = 0;
    }
}

/* Trim blanks at both ends in place; returns the start. */
static char *trim(char *s)
{
    while (*s == ' ' || *s == '\t') s++;
    size_t n = strlen(s);
    while (n && (s[n - 1] == ' ' || s[n - 1] == '\t' || s[n - 1] == '\r')) s[--n] = 0;
    return s;
}

/* A key and its value text. Leaves a message on error (no prefix). */
static int apply_text(scn_desc *d, ctx *cx, const char *key, char *value, char *err, size_t errlen)
{
    char *rest = trim(value);
    char copy[LINE_MAX_BYTES + 1];
    size_t rl = strlen(rest);
    if (rl > LINE_MAX_BYTES) return fail(err, errlen, "value too long");
    memcpy(copy, rest, rl + 1);
    char *t[MAX_TOK];
    int n = split(copy, t, MAX_TOK);
    if (n < 0) return fail(err, errlen, "%s: too many values (more than %d)", key, MAX_TOK);
    return apply(d, cx, key, t, n, rest, err, errlen);
}

int scn_desc_set(scn_desc *d, const char *key, const char *value, char *err, size_t errlen)
{
    char b[48];
    if (!key || !*key) {
        fail(err, errlen, "empty key");
        return -1;
    }
    if (!value) value = "";
    size_t vl = strlen(value);
    if (vl > LINE_MAX_BYTES) {
        fail(err, errlen, "%s: value too long", shown(key, b));
        return -1;
    }
    char v[LINE_MAX_BYTES + 1], msg[512];
    memcpy(v, value, vl + 1);
    scn_desc t = *d;
    ctx cx = { 0, 0, NULL, 0, SCN_LINE_SET };
    if (apply_text(&t, &cx, key, v, msg, sizeof msg)) {
        /* Messages of value errors start with the key already. */
        size_t kl = strlen(key);
        if (!strncmp(msg, key, kl) && (msg[kl] == ':' || msg[kl] == ' '))
            snprintf(err, errlen, "%s", msg);
        else
            snprintf(err, errlen, "%s: %s", shown(key, b), msg);
        return -1;
    }
    const double *e = t.view.cam.eye, *g = t.view.cam.target;
    if (e[0] == g[0] && e[1] == g[1] && e[2] == g[2]) {
        snprintf(err, errlen, "%s: eye and target are the same point", shown(key, b));
        return -1;
    }
    scn_desc_sync(&t);
    *d = t;
    return 0;
}

_Static_assert(K__COUNT <= SCN_DESC_NKEYS, "scn_desc.key_line is too small");

const char *scn_desc_where(const scn_desc *d, const char *const *keys, char *buf, size_t len)
{
    int best = 0, bk = -1;
    for (; *keys; keys++)
        for (int k = 0; k < K__COUNT; k++)
            if (!strcmp(*keys, scn_desc_keys[k]) && d->key_line[k] > best) { best = d->key_line[k]; bk = k; }
    if (bk < 0) snprintf(buf, len, "%s", "");
    else if (best == SCN_LINE_SET) snprintf(buf, len, "--set %s: ", scn_desc_keys[bk]);
    else snprintf(buf, len, "%s:%d: ", d->src, best);
    return buf;
}

int scn_desc_check_camera(const scn_desc *d, char *err, size_t errlen)
{
    static const char *const view[] = { "camera", "eye", "target", "up", "fov", "ortho-height", NULL };
    static const char *const held[] = { "camera", "eye", "target", "up", "fov", "ortho-height",
                                        "heldout-eye", "heldout-target", NULL };
    char msg[300], where[300];
    if (scn_camera_check(&d->view.cam, msg, sizeof msg)) {
        snprintf(err, errlen, "%s%s", scn_desc_where(d, view, where, sizeof where), msg);
        return -1;
    }
    if (scn_camera_check(&d->heldout.cam, msg, sizeof msg)) {
        snprintf(err, errlen, "%sheld-out view: %s", scn_desc_where(d, held, where, sizeof where), msg);
        return -1;
    }
    return 0;
}

/* Cut a comment: '#' at the start or after a blank. */
static void cut_comment(char *s)
{
    for (char *p = s; *p; p++)
        if (*p == '#' && (p == s || p[-1] == ' ' || p[-1] == '\t')) { *p = 0; return; }
}

int scn_desc_read(const char *path, scn_desc *d, char *err, size_t errlen)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(err, errlen, "%s: cannot open: %s", path, strerror(errno));
        return -1;
    }
    scn_desc *t = malloc(sizeof *t);
    char *line = malloc(LINE_MAX_BYTES + 1);
    if (!t || !line) {
        free(t); free(line); fclose(f);
        snprintf(err, errlen, "%s: out of memory", path);
        return -1;
    }
    scn_desc_default(t);
    const char *slash = strrchr(path, '/');
    ctx cx = { 1, 0, slash ? path : NULL, slash ? (size_t)(slash - path) : 0, 0 };
    snprintf(t->src, sizeof t->src, "%s", path);
    char msg[512];
    long ln = 0;
    int have_version = 0, rc = 0, cam_line = 0;
    for (;;) {
        long n = base_line_read(f, line, LINE_MAX_BYTES);
        if (n == BASE_LINE_EOF || n == BASE_LINE_ERR) break;
        ln++;
        if (n == BASE_LINE_LONG) { snprintf(err, errlen, "%s:%ld: line longer than %d bytes", path, ln, LINE_MAX_BYTES); rc = -1; break; }
        if (n == BASE_LINE_NUL) { snprintf(err, errlen, "%s:%ld: NUL byte: not a text file", path, ln); rc = -1; break; }
        cut_comment(line);
        char *s = trim(line);
        if (!*s) continue;
        size_t kl = strcspn(s, " \t");
        char *value = s + kl;
        if (*value) *value++ = 0;
        if (!have_version) {
            char *vt[4];
            char b[48];
            int nv = split(value, vt, 4);
            if (strcmp(s, "shadesim-scene")) {
                snprintf(err, errlen, "%s:%ld: not a shadesim scene file (the first line must be \"shadesim-scene 1\", not \"%s\")",
                         path, ln, shown(s, b));
                rc = -1;
                break;
            }
            if (nv != 1) {
                snprintf(err, errlen, "%s:%ld: the version line must be \"shadesim-scene 1\"", path, ln);
                rc = -1;
                break;
            }
            if (strcmp(vt[0], "1")) {
                snprintf(err, errlen, "%s:%ld: scene format version %s is not supported (this shadesim reads version 1)",
                         path, ln, shown(vt[0], b));
                rc = -1;
                break;
            }
            have_version = 1;
            continue;
        }
        if (!strcmp(s, "shadesim-scene")) {
            snprintf(err, errlen, "%s:%ld: the version line may only be the first line", path, ln);
            rc = -1;
            break;
        }
        cx.line = (int)(ln < SCN_LINE_SET ? ln : SCN_LINE_SET - 1);
        if (apply_text(t, &cx, s, value, msg, sizeof msg)) {
            snprintf(err, errlen, "%s:%ld: %s", path, ln, msg);
            rc = -1;
            break;
        }
        if (!strcmp(s, "eye") || !strcmp(s, "target")) cam_line = (int)ln;
    }
    if (!rc && ferror(f)) {
        snprintf(err, errlen, "%s: read error", path);
        rc = -1;
    }
    if (!rc && !have_version) {
        snprintf(err, errlen, "%s:%ld: empty: the first line must be \"shadesim-scene 1\"", path, ln + 1);
        rc = -1;
    }
    if (!rc) {
        const double *e = t->view.cam.eye, *g = t->view.cam.target;
        if (e[0] == g[0] && e[1] == g[1] && e[2] == g[2]) {
            snprintf(err, errlen, "%s:%d: eye and target are the same point", path, cam_line);
            rc = -1;
        }
    }
    if (!rc) {
        scn_desc_sync(t);
        *d = *t;
    }
    fclose(f);
    free(line);
    free(t);
    return rc;
}

/* ------------------------------------------------------------ writing */

/* The shortest of %.15g, %.16g, %.17g that reads back as the same double:
 * 0.05 rather than 0.050000000000000003, and still an exact round trip. */
typedef struct { char s[32]; } num_text;

static num_text txt(double x)
{
    num_text t;
    for (int p = 15; p <= 17; p++) {
        snprintf(t.s, sizeof t.s, "%.*g", p, x);
        if (strtod(t.s, NULL) == x) break;
    }
    return t;
}

static void put_light(FILE *f, const char *key, const scn_light *l)
{
    fprintf(f, "%s %s %s %s %s %s\n", key, l->point ? "point" : "directional",
            txt(l->v[0]).s, txt(l->v[1]).s, txt(l->v[2]).s, txt(l->intensity).s);
}

int scn_desc_write(FILE *f, const scn_desc *d)
{
    static const char *const dist[] = { "beckmann", "d4", "d8", "d16" };
    const scn_camera *c = &d->view.cam;
    int cook = d->mat.spec == SCN_SPEC_COOK ? d->mat.dg : d->cook_dg;
    int ward = d->mat.spec == SCN_SPEC_WARD ? d->mat.dg : d->ward_dg;
    int di = cook == 4 ? 1 : cook == 8 ? 2 : cook == 16 ? 3 : 0;
    fprintf(f, "shadesim-scene 1\n");
    fprintf(f, "mesh %s\n", d->mesh);
    fprintf(f, "detail %d\n", d->detail);
    fprintf(f, "resolution %dx%d\n", d->width, d->height);
    fprintf(f, "camera %s\n", c->perspective ? "perspective" : "ortho");
    fprintf(f, "eye %s %s %s\n", txt(c->eye[0]).s, txt(c->eye[1]).s, txt(c->eye[2]).s);
    fprintf(f, "target %s %s %s\n", txt(c->target[0]).s, txt(c->target[1]).s, txt(c->target[2]).s);
    fprintf(f, "up %s %s %s\n", txt(c->up[0]).s, txt(c->up[1]).s, txt(c->up[2]).s);
    fprintf(f, "fov %s\n", txt(c->fov_deg).s);
    fprintf(f, "ortho-height %s\n", txt(c->ortho_height).s);
    if (!d->view.nlights) fprintf(f, "light none\n");
    for (int i = 0; i < d->view.nlights && i < SCN_MAX_LIGHTS; i++)
        put_light(f, "light", &d->view.light[i]);
    const scn_camera *h = &d->heldout.cam;
    if (d->heldout_given & SCN_HELD_EYE)
        fprintf(f, "heldout-eye %s %s %s\n", txt(h->eye[0]).s, txt(h->eye[1]).s, txt(h->eye[2]).s);
    else
        fprintf(f, "heldout-eye auto  # %s %s %s\n", txt(h->eye[0]).s, txt(h->eye[1]).s, txt(h->eye[2]).s);
    if (d->heldout_given & SCN_HELD_TARGET)
        fprintf(f, "heldout-target %s %s %s\n", txt(h->target[0]).s, txt(h->target[1]).s, txt(h->target[2]).s);
    else
        fprintf(f, "heldout-target auto  # %s %s %s\n", txt(h->target[0]).s, txt(h->target[1]).s, txt(h->target[2]).s);
    if (d->heldout_given & SCN_HELD_LIGHT) {
        if (!d->heldout.nlights) fprintf(f, "heldout-light none\n");
        for (int i = 0; i < d->heldout.nlights && i < SCN_MAX_LIGHTS; i++)
            put_light(f, "heldout-light", &d->heldout.light[i]);
    } else {
        fprintf(f, "heldout-light auto\n");
        for (int i = 0; i < d->heldout.nlights && i < SCN_MAX_LIGHTS; i++) {
            fprintf(f, "# ");
            put_light(f, "heldout-light", &d->heldout.light[i]);
        }
    }
    const scn_material *m = &d->mat;
    fprintf(f, "ambient %s\n", txt(m->ambient).s);
    fprintf(f, "kd %s\n", txt(m->kd).s);
    fprintf(f, "ks %s\n", txt(m->ks).s);
    fprintf(f, "shininess %s\n", txt(m->shininess).s);
    fprintf(f, "specular %s\n", (unsigned)m->spec < SCN_SPEC__COUNT ? spec_names[m->spec] : "blinn");
    fprintf(f, "distribution %s\n", dist[di]);
    fprintf(f, "ward-form %s\n", ward ? "poly16" : "exact");
    fprintf(f, "roughness %s\n", txt(m->m).s);
    fprintf(f, "ward-alpha %s\n", txt(m->alpha).s);
    fprintf(f, "fresnel %s\n", (unsigned)m->fresnel < 3 ? fresnel_names[m->fresnel] : "none");
    fprintf(f, "fresnel-n %s\n", txt(m->fresnel_n).s);
    fprintf(f, "policy %s\n", scn_policy_name(d->policy));
    for (int r = 0; r < SCN_MAX_REGIONS; r++)
        fprintf(f, "region-degree %d %d\n", r, d->region_deg[r]);
    fprintf(f, "auto-threshold %s\n", txt(d->auto_threshold).s);
    fprintf(f, "auto-nodes n%d\n", d->auto_cubic_nodes == 2 ? 2 : 1);
    fprintf(f, "L %d\n", d->L);
    fprintf(f, "terms %d\n", d->terms);
    fprintf(f, "series %s\n", d->series ? "quarter" : "paper");
    fprintf(f, "width %d\n", d->fmt_width);
    if (!d->nfmt) fprintf(f, "fmt none\n");
    for (int i = 0; i < d->nfmt && i < SCN_MAX_FMT; i++) fprintf(f, "fmt %s\n", d->fmt[i]);
    fprintf(f, "round %s\n", (unsigned)d->rnd < 3 ? round_names[d->rnd] : "trunc");
    fprintf(f, "overflow %s\n", (unsigned)d->ovf < 2 ? ovf_names[d->ovf] : "wrap");
    fprintf(f, "schedule %s\n", d->schedule);
    fprintf(f, "cost");
    for (int i = 0; i < SCN_OP__COUNT; i++) fprintf(f, " %s=%s", scn_op_name[i], txt(d->cost[i]).s);
    fprintf(f, "\n");
    return ferror(f) ? -1 : 0;
}
