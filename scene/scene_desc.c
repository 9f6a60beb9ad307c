/* scene_desc.c - a scene description's values apart from reading them:
 * the defaults (the built-in "face" scene) and the other built-in scenes,
 * the held-out view that follows the view, where a value was set (for
 * errors found after reading), and writing a description back as a scene
 * file. The format itself, and reading it, is scene_file.c.
 */
#include "scene/scene_names.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define HELD_EYE_DEG   20.0
#define HELD_LIGHT_DEG 70.0

const char *const scn_op_name[SCN_OP__COUNT] = { "add", "mul", "div", "sqrt", "pow" };

const char *const scn_policy_names[SCN_POL__COUNT + 1] = {
    "linear", "quadratic", "cubic-n1", "cubic-n2", "adaptive-region", "adaptive-auto", NULL };
const char *const scn_spec_names[SCN_SPEC__COUNT + 1] = { "phong", "blinn", "cook", "ward", NULL };
const char *const scn_dist_names[] = { "beckmann", "d4", "d8", "d16", NULL };
const char *const scn_fresnel_names[] = { "none", "schlick", "mschlick", NULL };
const char *const scn_camera_names[] = { "ortho", "perspective", NULL };

const char *const scn_desc_builtin_names[] = { "face", "sphere", "torus", NULL };

const char *scn_policy_name(scn_policy p)
{
    return (unsigned)p < SCN_POL__COUNT ? scn_policy_names[p] : "?";
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
    /* L, terms, series, schedule, width, round, overflow: not set (the
     * unit's defaults) */
    d->nfmt = 0;
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

/* ------------------------------------------------- where a value was set */

const char *scn_desc_where(const scn_desc *d, const char *const *keys, char *buf, size_t len)
{
    int best = 0, bk = -1;
    for (; *keys; keys++)
        for (int k = 0; scn_desc_keys[k] && k < SCN_DESC_NKEYS; k++)
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
    fprintf(f, "specular %s\n", (unsigned)m->spec < SCN_SPEC__COUNT ? scn_spec_names[m->spec] : "blinn");
    fprintf(f, "distribution %s\n", scn_dist_names[di]);
    fprintf(f, "ward-form %s\n", ward ? "poly16" : "exact");
    fprintf(f, "roughness %s\n", txt(m->m).s);
    fprintf(f, "ward-alpha %s\n", txt(m->alpha).s);
    fprintf(f, "fresnel %s\n", (unsigned)m->fresnel < 3 ? scn_fresnel_names[m->fresnel] : "none");
    fprintf(f, "fresnel-n %s\n", txt(m->fresnel_n).s);
    fprintf(f, "policy %s\n", scn_policy_name(d->policy));
    for (int r = 0; r < SCN_MAX_REGIONS; r++)
        fprintf(f, "region-degree %d %d\n", r, d->region_deg[r]);
    fprintf(f, "auto-threshold %s\n", txt(d->auto_threshold).s);
    fprintf(f, "auto-nodes n%d\n", d->auto_cubic_nodes == 2 ? 2 : 1);
    /* the unit's parameters only where set: else its defaults */
    if (*d->L) fprintf(f, "L %s\n", d->L);
    if (*d->terms) fprintf(f, "terms %s\n", d->terms);
    if (*d->series) fprintf(f, "series %s\n", d->series);
    if (*d->fmt_width) fprintf(f, "width %s\n", d->fmt_width);
    if (!d->nfmt) fprintf(f, "fmt none\n");
    for (int i = 0; i < d->nfmt && i < SCN_MAX_FMT; i++) fprintf(f, "fmt %s\n", d->fmt[i]);
    if (*d->rnd) fprintf(f, "round %s\n", d->rnd);
    if (*d->ovf) fprintf(f, "overflow %s\n", d->ovf);
    if (*d->schedule) fprintf(f, "schedule %s\n", d->schedule);
    if (*d->unit) fprintf(f, "unit %s\n", d->unit);
    fprintf(f, "cost");
    for (int i = 0; i < SCN_OP__COUNT; i++) fprintf(f, " %s=%s", scn_op_name[i], txt(d->cost[i]).s);
    fprintf(f, "\n");
    return ferror(f) ? -1 : 0;
}
