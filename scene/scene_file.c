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
 *                (L, terms, series and schedule are the unit's parameters:
 *                their ranges, choices and defaults are its descriptor's;
 *                width, round and overflow are every unit's settings, with
 *                its defaults; all applied when the scene's unit is set
 *                up; not set, the description holds "")
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
#include "base/base_out.h"
#include "scene/scene_names.h"
#include "base/base_join.h"
#include "base/base_line.h"
#include "base/base_num.h"
#include "base/base_near.h"
#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#define LINE_MAX_BYTES 4095
#define MAX_TOK 40

/* ---------------------------------------------------- value parsing */

typedef struct ctx {
    int         from_file;          /* 1: scn_desc_read (first light line replaces) */
    int         light_seen;         /* a light line was read from this file */
    const char *dir;                /* scene file's folder (dirlen bytes), NULL: none */
    size_t      dirlen;             /* 0 with dir set: the root, "/" */
    int         line;               /* the line being applied (SCN_LINE_SET: --set) */
    const char *rest;               /* its value text as written (mesh reads it) */
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

/* A token shown in a message: its bytes, at most 40 (then "..."). */
static const char *shown(const char *s, char buf[48])
{
    /* the CLI's printer keeps UTF-8 and writes other bytes as \xNN */
    size_t i = 0;
    for (; s[i] && i < 40; i++) buf[i] = s[i];
    if (s[i]) {
        while (i > 0 && ((unsigned char)s[i] & 0xC0) == 0x80) i--;
        buf[i++] = '.'; buf[i++] = '.'; buf[i++] = '.';
    }
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

/* A key's row: how its values are read and where they go. INT, REAL and
 * NAME keys take one value into the field at off (INT and NAME an int,
 * REAL a double) with the same checks and messages; CALL keys have a
 * reader of their own. */
typedef enum { KT_INT, KT_REAL, KT_NAME, KT_CALL } key_type;
typedef struct key_row key_row;
typedef int key_fn(scn_desc *d, ctx *cx, const key_row *k, char **t, int n, char *err, size_t errlen);
struct key_row {
    key_type    type;
    size_t      off;                /* offsetof(scn_desc, field) */
    double      lo, hi;             /* INT, REAL: the range */
    const char *what;               /* the value, as "takes 1 value (WHAT)" names it */
    const char *const *names;       /* NAME: the choices, NULL-terminated */
    const int  *vals;               /* NAME: the value of each choice (NULL: its index) */
    key_fn     *call;               /* CALL */
    int         dg;                 /* NAME: mat.dg follows (set_dg) */
    const char *name;               /* set from the key list (KEY_ROW) */
};

static key_fn k_mesh, k_res, k_vec, k_fov, k_oheight, k_light, k_held, k_regdeg, k_fmt, k_whole, k_word, k_cost;

#define F(field) offsetof(scn_desc, field)
#define INT(field, lo_, hi_, wh_) .type = KT_INT, .off = F(field), .lo = lo_, .hi = hi_, .what = wh_
#define REAL(field, lo_, hi_, wh_) .type = KT_REAL, .off = F(field), .lo = lo_, .hi = hi_, .what = wh_
#define NAME(field, nm_, wh_) .type = KT_NAME, .off = F(field), .names = nm_, .what = wh_
#define CALL(fn_) .type = KT_CALL, .call = fn_
#define WHOLE(field, lo_, hi_, wh_) CALL(k_whole), .off = F(field), .lo = lo_, .hi = hi_, .what = wh_

static const int dist_g[] = { 0, 4, 8, 16 }, ward_g[] = { 0, 16 }, nodes_v[] = { 1, 2 };
static const char *const ward_names[] = { "exact", "poly16", NULL };
static const char *const nodes_names[] = { "n1", "n2", NULL };

/* Every key once, in the order of the table at the top: its index is
 * key_line's (K_<ID>), its name scn_desc_keys', its row keys[]. The
 * hardware's parameters L, terms, series and its schedule are the unit's:
 * this layer keeps the whole number or the name as text (k_whole,
 * k_word; "" when not set), and the testbench applies them through the
 * unit's own setters (tb_scene_unit), with the ranges, choices and
 * defaults of the unit's descriptor. */
#define SCN_KEYS(X) \
    X(MESH,      "mesh",           CALL(k_mesh), .off = F(mesh), .what = "a built-in name or an OBJ path") \
    X(DETAIL,    "detail",         INT(detail, 1, 8, "N")) \
    X(RES,       "resolution",     CALL(k_res)) \
    X(CAMERA,    "camera",         NAME(view.cam.perspective, scn_camera_names, "ortho|perspective")) \
    X(EYE,       "eye",            CALL(k_vec), .off = F(view.cam.eye)) \
    X(TARGET,    "target",         CALL(k_vec), .off = F(view.cam.target)) \
    X(UP,        "up",             CALL(k_vec), .off = F(view.cam.up)) \
    X(FOV,       "fov",            CALL(k_fov)) \
    X(OHEIGHT,   "ortho-height",   CALL(k_oheight)) \
    X(LIGHT,     "light",          CALL(k_light)) \
    X(HEYE,      "heldout-eye",    CALL(k_held), .off = F(heldout.cam.eye)) \
    X(HTARGET,   "heldout-target", CALL(k_held), .off = F(heldout.cam.target)) \
    X(HLIGHT,    "heldout-light",  CALL(k_light)) \
    X(AMBIENT,   "ambient",        REAL(mat.ambient, 0.0, 1.0, "a number in [0, 1]")) \
    X(KD,        "kd",             REAL(mat.kd, 0.0, 1.0, "a number in [0, 1]")) \
    X(KS,        "ks",             REAL(mat.ks, 0.0, 1.0, "a number in [0, 1]")) \
    X(SHININESS, "shininess",      REAL(mat.shininess, 0.0, 10000.0, "N")) \
    X(SPECULAR,  "specular",       NAME(mat.spec, scn_spec_names, "phong|blinn|cook|ward"), .dg = 1) \
    X(DIST,      "distribution",   NAME(cook_dg, scn_dist_names, "beckmann|d4|d8|d16"), .vals = dist_g, .dg = 1) \
    X(WARDFORM,  "ward-form",      NAME(ward_dg, ward_names, "exact|poly16"), .vals = ward_g, .dg = 1) \
    X(ROUGH,     "roughness",      REAL(mat.m, 0.01, 1.0, "a number in [0.01, 1]")) \
    X(WALPHA,    "ward-alpha",     REAL(mat.alpha, 0.01, 1.0, "a number in [0.01, 1]")) \
    X(FRESNEL,   "fresnel",        NAME(mat.fresnel, scn_fresnel_names, "none|schlick|mschlick")) \
    X(FRESN,     "fresnel-n",      REAL(mat.fresnel_n, 1.0, 10000.0, "N")) \
    X(POLICY,    "policy",         NAME(policy, scn_policy_names, "a policy name")) \
    X(REGDEG,    "region-degree",  CALL(k_regdeg)) \
    X(ATHRESH,   "auto-threshold", REAL(auto_threshold, 0.0, 1e6, "X")) \
    X(ANODES,    "auto-nodes",     NAME(auto_cubic_nodes, nodes_names, "n1|n2"), .vals = nodes_v) \
    X(L,         "L",              WHOLE(L, INT_MIN, INT_MAX, "N")) \
    X(TERMS,     "terms",          WHOLE(terms, INT_MIN, INT_MAX, "N")) \
    X(SERIES,    "series",         CALL(k_word), .off = F(series), .what = "paper|quarter") \
    X(WIDTH,     "width",          WHOLE(fmt_width, 4, 64, "W")) \
    X(FMT,       "fmt",            CALL(k_fmt)) \
    X(ROUND,     "round",          CALL(k_word), .off = F(rnd), .what = "trunc|half-up|even") \
    X(OVERFLOW,  "overflow",       CALL(k_word), .off = F(ovf), .what = "wrap|sat") \
    X(SCHEDULE,  "schedule",       CALL(k_word), .off = F(schedule), .what = "paper|mac|pipe") \
    X(UNIT,      "unit",           CALL(k_mesh), .off = F(unit), .what = "a datapath file's path") \
    X(COST,      "cost",           CALL(k_cost))

#define KEY_ID(id, nm, ...) K_##id,
#define KEY_NAME(id, nm, ...) nm,
#define KEY_ROW(id, nm, ...) { __VA_ARGS__, .name = nm },
enum { SCN_KEYS(KEY_ID) K__COUNT };
const char *const scn_desc_keys[K__COUNT + 1] = { SCN_KEYS(KEY_NAME) NULL };
static const key_row keys[K__COUNT] = { SCN_KEYS(KEY_ROW) };
/* NAME keys store an int; the enum fields among them must be one */
_Static_assert(sizeof(scn_spec_model) == sizeof(int) && sizeof(scn_fresnel) == sizeof(int)
               && sizeof(scn_policy) == sizeof(int), "enum fields are ints");

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

/* mesh, unit: the rest of the line, a path (mesh: or a built-in name)
 * relative to the file's folder; into a char[256] at k->off. */
static int k_mesh(scn_desc *d, ctx *cx, const key_row *k, char **t, int n, char *err, size_t errlen)
{
    (void)t; (void)n;
    const char *rest = cx->rest, *dir = cx->dir;
    char *dst = (char *)d + k->off;
    if (!rest || !*rest) return fail(err, errlen, "%s: takes %s", k->name, k->what);
    for (int i = 0; k->off == offsetof(scn_desc, mesh) && scn_desc_builtin_names[i]; i++)
        if (!strcmp(rest, scn_desc_builtin_names[i])) dir = NULL;   /* a built-in name */
    size_t rl = strlen(rest), dl = rest[0] == '/' || !dir ? 0 : cx->dirlen + 1;
    if (dl + rl >= sizeof d->mesh) return fail(err, errlen, "%s: path too long", k->name);
    if (dl) { memcpy(dst, dir, dl - 1); dst[dl - 1] = '/'; }
    memcpy(dst + dl, rest, rl + 1);
    return 0;
}

static int k_res(scn_desc *d, ctx *cx, const key_row *k, char **t, int n, char *err, size_t errlen)
{
    (void)cx;
    if (count(k->name, n, 1, 1, "WxH", err, errlen)) return -1;
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

/* eye, target, up: X Y Z into the double[3] at off (up not zero). */
static int k_vec(scn_desc *d, ctx *cx, const key_row *k, char **t, int n, char *err, size_t errlen)
{
    (void)cx;
    if (count(k->name, n, 3, 3, "X Y Z", err, errlen)) return -1;
    double v[3];
    if (vec3(k->name, t, v, err, errlen)) return -1;
    if (k->off == F(view.cam.up) && v[0] == 0.0 && v[1] == 0.0 && v[2] == 0.0)
        return fail(err, errlen, "up: a direction of length 0");
    memcpy((char *)d + k->off, v, sizeof v);
    return 0;
}

static int k_fov(scn_desc *d, ctx *cx, const key_row *k, char **t, int n, char *err, size_t errlen)
{
    (void)cx;
    double x;
    if (count(k->name, n, 1, 1, "degrees", err, errlen)) return -1;
    if (num(k->name, t[0], 0.0, 180.0, &x, err, errlen)) return -1;
    if (x <= 0.0 || x >= 180.0)
        return fail(err, errlen, "fov: %g is out of range (0 < fov < 180)", x);
    d->view.cam.fov_deg = x;
    return 0;
}

static int k_oheight(scn_desc *d, ctx *cx, const key_row *k, char **t, int n, char *err, size_t errlen)
{
    (void)cx;
    double x;
    if (count(k->name, n, 1, 1, "H", err, errlen)) return -1;
    if (num(k->name, t[0], 0.0, 1e6, &x, err, errlen)) return -1;
    if (x <= 0.0) return fail(err, errlen, "ortho-height: must be > 0");
    d->view.cam.ortho_height = x;
    return 0;
}

/* light, heldout-light: none, auto (held-out), or one more light. */
static int k_light(scn_desc *d, ctx *cx, const key_row *k, char **t, int n, char *err, size_t errlen)
{
    int view = k == &keys[K_LIGHT];
    scn_view *v = view ? &d->view : &d->heldout;
    if (n == 1 && !strcmp(t[0], "none")) {
        v->nlights = 0;
        if (view) cx->light_seen = 1;
        else d->heldout_given |= SCN_HELD_LIGHT;
        return 0;
    }
    if (!view && n == 1 && !strcmp(t[0], "auto")) {
        d->heldout_given &= ~SCN_HELD_LIGHT;
        return 0;
    }
    scn_light l;
    if (light_of(k->name, t, n, &l, err, errlen)) return -1;
    if (view) {
        if (cx->from_file && !cx->light_seen) v->nlights = 0;
        cx->light_seen = 1;
    } else if (!(d->heldout_given & SCN_HELD_LIGHT)) {
        v->nlights = 0;
        d->heldout_given |= SCN_HELD_LIGHT;
    }
    if (v->nlights >= SCN_MAX_LIGHTS)
        return fail(err, errlen, "%s: too many lights (at most %d)", k->name, SCN_MAX_LIGHTS);
    v->light[v->nlights++] = l;
    return 0;
}

/* heldout-eye, heldout-target: auto, or X Y Z into the double[3] at off. */
static int k_held(scn_desc *d, ctx *cx, const key_row *k, char **t, int n, char *err, size_t errlen)
{
    (void)cx;
    unsigned bit = k == &keys[K_HEYE] ? SCN_HELD_EYE : SCN_HELD_TARGET;
    if (n == 1 && !strcmp(t[0], "auto")) { d->heldout_given &= ~bit; return 0; }
    if (count(k->name, n, 3, 3, "auto or X Y Z", err, errlen)) return -1;
    if (vec3(k->name, t, (double *)((char *)d + k->off), err, errlen)) return -1;
    d->heldout_given |= bit;
    return 0;
}

static int k_regdeg(scn_desc *d, ctx *cx, const key_row *k, char **t, int n, char *err, size_t errlen)
{
    (void)cx;
    if (count(k->name, n, 2, 2, "REGION DEGREE", err, errlen)) return -1;
    int r, g;
    if (inum("region-degree region", t[0], 0, SCN_MAX_REGIONS - 1, &r, err, errlen) ||
        inum("region-degree degree", t[1], 2, 3, &g, err, errlen)) return -1;
    d->region_deg[r] = (uint8_t)g;
    return 0;
}

/* fmt: none clears; each NAME=sI.F appends. */
static int k_fmt(scn_desc *d, ctx *cx, const key_row *k, char **t, int n, char *err, size_t errlen)
{
    (void)cx; (void)k;
    if (n == 1 && !strcmp(t[0], "none")) { d->nfmt = 0; return 0; }
    if (n < 1) return fail(err, errlen, "fmt: takes none or NAME=sI.F values, got none");
    for (int i = 0; i < n; i++) {
        if (fmt_ok(t[i], err, errlen)) return -1;
        if (d->nfmt >= SCN_MAX_FMT)
            return fail(err, errlen, "fmt: too many formats (at most %d)", SCN_MAX_FMT);
        strcpy(d->fmt[d->nfmt++], t[i]);
    }
    return 0;
}

/* L, terms, width: a whole number in the row's range (L's and terms'
 * are the unit's: any int here), kept as text at off. */
static int k_whole(scn_desc *d, ctx *cx, const key_row *k, char **t, int n, char *err, size_t errlen)
{
    (void)cx;
    int v;
    if (count(k->name, n, 1, 1, k->what, err, errlen)) return -1;
    if (inum(k->name, t[0], (long)k->lo, (long)k->hi, &v, err, errlen)) return -1;
    snprintf((char *)d + k->off, sizeof d->L, "%d", v);     /* at most 11 bytes */
    return 0;
}

/* series, schedule, round, overflow: a name the unit judges (its
 * choices, its schedules, the simulator's modes: tb_scene_unit), kept as
 * text at off. */
static int k_word(scn_desc *d, ctx *cx, const key_row *k, char **t, int n, char *err, size_t errlen)
{
    (void)cx;
    char b[48];
    if (count(k->name, n, 1, 1, k->what, err, errlen)) return -1;
    if (strlen(t[0]) >= sizeof d->schedule) return fail(err, errlen, "%s: \"%s\" is too long", k->name, shown(t[0], b));
    strcpy((char *)d + k->off, t[0]);
    return 0;
}

/* cost: OP=W values, each sets one weight. */
static int k_cost(scn_desc *d, ctx *cx, const key_row *k, char **t, int n, char *err, size_t errlen)
{
    (void)cx; (void)k;
    if (n < 1) return fail(err, errlen, "cost: takes OP=W values (OP add mul div sqrt pow), got none");
    for (int i = 0; i < n; i++) {
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
    const key_row *r = &keys[k];
    char *field = (char *)d + r->off;
    int i;
    switch (r->type) {
    case KT_CALL:
        cx->rest = rest;
        return r->call(d, cx, r, t, n, err, errlen);
    case KT_INT:
        if (count(key, n, 1, 1, r->what, err, errlen)) return -1;
        return inum(key, t[0], (long)r->lo, (long)r->hi, (int *)field, err, errlen);
    case KT_REAL:
        if (count(key, n, 1, 1, r->what, err, errlen)) return -1;
        return num(key, t[0], r->lo, r->hi, (double *)field, err, errlen);
    case KT_NAME:
        if (count(key, n, 1, 1, r->what, err, errlen)) return -1;
        if ((i = pick(key, t[0], r->names, -1, err, errlen)) < 0) return -1;
        *(int *)field = r->vals ? r->vals[i] : i;
        if (r->dg) set_dg(d);
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
    ctx cx = { 0, 0, NULL, 0, SCN_LINE_SET, NULL };
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
/* k_whole and k_word write any of these at the size of one */
#define SAME_SIZE(a, b) (sizeof ((scn_desc *)0)->a == sizeof ((scn_desc *)0)->b)
_Static_assert(SAME_SIZE(terms, L) && SAME_SIZE(series, L) && SAME_SIZE(schedule, L) && SAME_SIZE(fmt_width, L)
               && SAME_SIZE(rnd, L) && SAME_SIZE(ovf, L), "hardware key fields");

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
    if (!t || !line) base_out_of_memory();
    scn_desc_default(t);
    const char *slash = strrchr(path, '/');
    ctx cx = { 1, 0, slash ? path : NULL, slash ? (size_t)(slash - path) : 0, 0, NULL };
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
