/* tb_scene_pipes.c - a scene through both pipelines in hardware: the
 * per-pixel reference and the method's nodes on the shade unit
 * (tb_scene_pipes.h). */
#include "testbench/study/tb_scene_pipes.h"
static const unit_desc *shade_unit(const scn_desc *d);
#include "testbench/tb_items_memo.h"
#include "testbench/tb_widths.h"
#include "base/base_json.h"
#include "base/base_out.h"
#include "vectors/ref_brdf.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define SHADE_IN_MAX 13            /* nx ny nz, then the frame's constants */
#define FRAME_MAX (SHADE_IN_MAX - 3)

static int unit3(const double v[3], double u[3])
{
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (!(l > 0) || !isfinite(l)) return 0;
    for (int e = 0; e < 3; e++) u[e] = v[e] / l;
    return 1;
}

/* The unit that shades d's material: shade (Blinn, or no specular term)
 * or shade_cook (Cook-Torrance with D_g); NULL for the others. */
const unit_desc *tb_scene_pipes_unit(const scn_desc *d) { return shade_unit(d); }

static const unit_desc *shade_unit(const scn_desc *d)
{
    const scn_material *mt = &d->mat;
    if (mt->ks == 0 || mt->spec == SCN_SPEC_BLINN) return unit_find("shade");
    if (mt->spec == SCN_SPEC_COOK && mt->dg) return unit_find("shade_cook");
    return NULL;
}
static int is_cook(const unit_desc *u) { return u && !strcmp(u->name, "shade_cook"); }

/* A real parameter's range check. */
static int real_in(const unit_desc *u, const char *name, double v)
{
    for (int k = 0; u && k < u->nparams; k++)
        if (!strcmp(u->params[k].name, name)) return v >= u->params[k].min && v <= u->params[k].max;
    return 0;
}

/* The frame's V (towards the viewer) and L, unit. */
static void frame_lv(const scn_view *v, double V[3], double L[3])
{
    const scn_camera *c = &v->cam;
    double vs[3] = { c->eye[0] - c->target[0], c->eye[1] - c->target[1], c->eye[2] - c->target[2] };
    unit3(vs, V);
    unit3(v->light[0].v, L);
}

/* The shininess as the unit's whole exponent n, or -1 when it is none or
 * outside the unit's range. */
static int shade_n(const unit_desc *u, double shininess)
{
    for (int k = 0; u && k < u->nparams; k++)
        if (!strcmp(u->params[k].name, "n")) {
            const unit_param *p = &u->params[k];
            return shininess == floor(shininess) && shininess >= p->min && shininess <= p->max ? (int)shininess : -1;
        }
    return -1;
}

int tb_scene_pipes_fit(const scn_desc *d, const scn_view *v, char *why, size_t len)
{
    const scn_material *mt = &d->mat;
    const char *no = NULL;
    const unit_desc *u = shade_unit(d);
    double V[3], L[3];
    if (!u) no = mt->spec == SCN_SPEC_COOK ? "the shade units compute Cook-Torrance with D_g only (distribution d4, d8 or d16)"
                                           : "the shade units compute Blinn's and Cook-Torrance's (D_g) highlights only";
    else if (v->nlights != 1 || v->light[0].point) no = "the shade unit takes one directional light";
    else if (v->cam.perspective) no = "the shade unit takes an orthographic camera (V constant)";
    else if (!is_cook(u) && mt->ks != 0 && shade_n(u, mt->shininess) < 0)
        no = "the shade unit's exponent n is a whole number in its range (shadesim list shade)";
    else if (is_cook(u) && !real_in(u, "m", mt->m))
        no = "shade_cook's roughness m is in its range (shadesim list shade_cook)";
    else if (mt->kd * v->light[0].intensity > 1 || mt->ks * v->light[0].intensity > 1)
        no = "kd and ks times the light's intensity must stay within [0, 1]";
    else if (is_cook(u) && (frame_lv(v, V, L), V[0] * L[0] + V[1] * L[1] + V[2] * L[2] < -0.5))
        no = "shade_cook takes a light within 120 degrees of the view (V.H >= 1/2)";
    if (no) snprintf(why, len, "%s", no);
    return !no;
}

/* One item's inputs: N scaled by a power of two into |N| in [1/2, 1)
 * (a shift: the direction is exact), then the frame's nfr constants. */
static void item_in(const double n[3], const double *fr, int nfr, double *row)
{
    double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    int e = 0;
    if (l > 0 && isfinite(l)) (void)frexp(l, &e);
    for (int k = 0; k < 3; k++) row[k] = ldexp(n[k], -e);
    memcpy(row + 3, fr, (size_t)nfr * sizeof *row);
}

/* The frame's constants, their count returned: shade's L, H =
 * normalize(L + V), ka, kd I0, ks I0; shade_cook's L, V, hs = 1/|L + V|,
 * ka, kd I0 and kc = ks I0 F(L.H) / pi (the Fresnel factor on L.H = V.H,
 * constant over the frame, and Cook and Torrance's 1/pi;
 * scene/scene_shade.c). */
static int frame(const scn_desc *d, const scn_view *v, double *fr)
{
    double V[3], L[3], h[3], H[3];
    frame_lv(v, V, L);
    for (int k = 0; k < 3; k++) h[k] = L[k] + V[k];
    if (!unit3(h, H)) memcpy(H, L, sizeof L);
    double I0 = v->light[0].intensity;
    memcpy(fr, L, sizeof L);
    if (is_cook(shade_unit(d))) {
        const scn_material *mt = &d->mat;
        double lh = L[0] * H[0] + L[1] * H[1] + L[2] * H[2], f = 1, hl = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
        if (mt->fresnel == SCN_FRESNEL_SCHLICK) f = ref_brdf_schlick(lh, mt->fresnel_n);
        else if (mt->fresnel == SCN_FRESNEL_MSCHLICK) f = ref_brdf_mschlick(lh, mt->fresnel_n);
        memcpy(fr + 3, V, sizeof V);
        fr[6] = hl > 0 ? 1 / hl : 1;
        fr[7] = mt->ambient;
        fr[8] = mt->kd * I0;
        fr[9] = mt->ks * I0 * f / M_PI;
        return 10;
    }
    memcpy(fr + 3, H, sizeof H);
    fr[6] = d->mat.ambient;
    fr[7] = d->mat.kd * I0;
    fr[8] = d->mat.ks * I0;
    return 9;
}

static double nmse_of(const tb_scene_result *r, const double *img)
{
    double se = 0, sr = 0;
    for (size_t i = 0; i < (size_t)r->w * r->h; i++) {
        if (!r->deg[i]) continue;
        double e = img[i] - r->ref[i];
        se += e * e;
        sr += r->ref[i] * r->ref[i];
    }
    return sr > 0 ? se / sr : (se > 0 ? INFINITY : 0);
}

/* The shade unit at schedule k: configuration, formats, f_max. */
typedef struct shader {
    const unit_desc *u;
    unit_cfg cfg;
    unit_fmts f;
    tb_ppa ppa;
} shader;

static int shader_at(const scn_desc *d, int width, int k, shader *s, char *err, size_t errlen)
{
    s->u = shade_unit(d);
    unit_cfg_default(s->u, &s->cfg);
    s->cfg.width = width;
    s->cfg.schedule = k;
    if (is_cook(s->u)) {
        s->cfg.m = d->mat.m;
        s->cfg.g = d->mat.dg;
    } else {
        int n = shade_n(s->u, d->mat.shininess);
        if (n > 0) s->cfg.n = n;
    }
    if (tb_formats(s->u, &s->cfg, NULL, 0, &s->f, err, errlen)) return -1;
    return tb_unit_timing(s->u, &s->cfg, &s->f, &s->ppa, err, errlen);
}

static void derive(tb_pipe_row *w)
{
    w->pixels_per_s = w->clocks_per_pixel > 0 ? w->fmax_mhz * 1e6 / w->clocks_per_pixel : 0;
    w->pps_per_kge = w->area_ge > 0 ? w->pixels_per_s / (w->area_ge / 1e3) : 0;
    w->ge_per_mpps = w->pixels_per_s > 0 ? w->area_ge / (w->pixels_per_s / 1e6) : INFINITY;
}

/* The method's pipeline: one node shader feeding k span units side by
 * side (each its own spans), k in 1..TB_PIPES_KMAX the one with the most
 * pixels per second per kGE (the fewest of equals): a pixel every
 * max(span clocks per pixel / k, shade clocks per node x nodes per pixel)
 * clocks, area shade + k span units. */
static void balance(tb_pipe_row *b)
{
    tb_pipe_row best = *b;
    for (int k = 1; k <= TB_PIPES_KMAX; k++) {
        tb_pipe_row w = *b;
        w.spans = k;
        w.clocks_per_pixel = fmax(w.span_cpp / k, w.shade_cpi * w.nodes_per_pixel);
        w.area_ge = w.shade_area + k * w.span_area;
        derive(&w);
        if (k == 1 || w.pps_per_kge > best.pps_per_kge) best = w;
    }
    *b = best;
}

/* The normals of every band, in band order, as the unit's inputs. */
static double *inputs(const tb_scene_nodes *rec, int nodes, const double *fr, int nfr, size_t *n)
{
    int ni = 3 + nfr;
    size_t t = 0;
    for (int k = 0; k < TB_SCENE_BANDS; k++) t += nodes ? rec->band[k].nnodes : rec->band[k].npix;
    double *in = malloc((t ? t : 1) * (size_t)ni * sizeof *in);
    if (!in) base_out_of_memory();
    size_t i = 0;
    for (int k = 0; k < TB_SCENE_BANDS; k++) {
        const tb_scene_nodes_band *b = &rec->band[k];
        size_t m = nodes ? b->nnodes : b->npix;
        for (size_t j = 0; j < m; j++, i++) item_in(nodes ? b->nn[j] : b->pn[j], fr, nfr, in + i * (size_t)ni);
    }
    *n = t;
    return in;
}

/* The render of d as the pipelines need it: of mesh m, or on surface
 * buffer g when given (a sweep's, rasterized once). */
static int render_of(const scn_desc *d, const scn_mesh *m, const scn_gbuf *g, const tb_scene_opts *o,
                     tb_scene_result *r, char *err, size_t errlen)
{
    return g ? tb_scene_render_gbuf(d, g, NULL, NULL, o, r, err, errlen) : tb_scene_render(d, m, o, r, err, errlen);
}

/* The reference's row at schedule s: every recorded pixel through the
 * unit; the image into *img (NULL: not kept). */
static int ref_row(const tb_scene_result *r, const tb_scene_nodes *rec, const shader *s, const double *fr, int nfr,
                   int jobs, tb_pipe_row *a, double **img, char *err, size_t errlen)
{
    size_t np, npx = (size_t)r->w * r->h;
    double *pin = inputs(rec, 0, fr, nfr, &np);
    double *pout = malloc((np ? np : 1) * sizeof *pout), *im = calloc(npx ? npx : 1, sizeof *im);
    if (!pout || !im) base_out_of_memory();
    tb_items_stats ps;
    int rc = tb_items_run(s->u, &s->cfg, &s->f, pin, np, jobs, 1, pout, &ps, err, errlen);
    if (rc == TB_OK) {
        size_t i = 0;
        for (int k = 0; k < TB_SCENE_BANDS; k++)
            for (size_t j = 0; j < rec->band[k].npix; j++) im[rec->band[k].pix[j]] = pout[i++];
        memset(a, 0, sizeof *a);
        snprintf(a->sched, sizeof a->sched, "%s", s->u->sched[s->cfg.schedule].name);
        a->width = s->cfg.width;
        a->shade_cpi = a->clocks_per_pixel = ps.cycles_per_item;
        a->shade_area = a->area_ge = ps.area_ge;
        a->shade_fmax = a->fmax_mhz = s->ppa.fmax_mhz;
        a->shade_pj = a->pj_per_pixel = ps.items ? ps.energy_pj / (double)ps.items : 0;
        a->nmse = nmse_of(r, im);
        a->overflows = ps.overflows + ps.in_overflows;
        derive(a);
    }
    if (rc == TB_OK && img) *img = im;
    else free(im);
    free(pin);
    free(pout);
    return rc;
}

/* The method's row at schedule s: the recorded nodes through the unit,
 * replayed into a render of d; its hardware image into *img (NULL: not
 * kept). */
static int method_row(const scn_desc *d, const scn_mesh *m, const scn_gbuf *g, const tb_scene_opts *o,
                      const tb_scene_result *r, tb_scene_nodes *rec, const shader *s, const double *fr, int nfr,
                      tb_pipe_row *b, double **img, char *err, size_t errlen)
{
    size_t nn;
    double *nin = inputs(rec, 1, fr, nfr, &nn), *nout = malloc((nn ? nn : 1) * sizeof *nout);
    if (!nout) base_out_of_memory();
    tb_items_stats ns;
    int rc = tb_items_run_memo(o->memo, s->u, &s->cfg, &s->f, nin, nn, o->jobs < 1 ? 1 : o->jobs, 1, nout, &ns,
                               err, errlen);
    tb_scene_result r2;
    memset(&r2, 0, sizeof r2);
    if (rc == TB_OK) {
        rec->replay = 1;
        for (int k = 0, off = 0; k < TB_SCENE_BANDS; off += (int)rec->band[k].nnodes, k++) {
            rec->band[k].val = nout + off;
            rec->band[k].next = 0;
        }
        tb_scene_opts o2 = *o;
        o2.nodes = rec;
        o2.energy = 1;
        o2.vcd_path = NULL;
        rc = render_of(d, m, g, &o2, &r2, err, errlen);
    }
    if (rc == TB_OK) {
        memset(b, 0, sizeof *b);
        b->method = 1;
        snprintf(b->sched, sizeof b->sched, "%s", s->u->sched[s->cfg.schedule].name);
        b->width = s->cfg.width;
        b->shade_cpi = ns.cycles_per_item;
        b->shade_area = ns.area_ge;
        b->shade_fmax = s->ppa.fmax_mhz;
        b->shade_pj = ns.items ? ns.energy_pj / (double)ns.items : 0;
        b->nmse = r2.nmse;
        b->overflows = ns.overflows + ns.in_overflows + r2.hwst.overflows;
        b->nodes_per_pixel = r2.covered ? (double)r2.nodes_shaded / (double)r2.covered : 0;
        b->span_cpp = r2.clocks_per_pixel;
        b->span_area = r2.hwst.area_ge;
        b->span_fmax = r->speed.hw.fmax_mhz;
        b->span_pj = r2.energy_pj_per_pixel;
        b->fmax_mhz = fmin(b->span_fmax, b->shade_fmax);
        b->pj_per_pixel = b->span_pj + b->shade_pj * b->nodes_per_pixel;
        balance(b);
        if (img) { *img = r2.hw; r2.hw = NULL; }
    }
    tb_scene_free(&r2);
    free(nin);
    free(nout);
    return rc;
}

int tb_scene_pipes_run(const scn_desc *d, const scn_mesh *m, const scn_gbuf *g, const tb_scene_opts *o,
                       const tb_scene_result *r, tb_scene_nodes *rec, int width, int which, tb_scene_pipes *p,
                       char *err, size_t errlen)
{
    memset(p, 0, sizeof *p);
    const scn_view *v = r->heldout ? &d->heldout : &d->view;
    p->w = r->w;
    p->h = r->h;
    p->width = width;
    if (!tb_scene_pipes_fit(d, v, p->why, sizeof p->why)) return TB_OK;
    const unit_desc *u = shade_unit(d);
    snprintf(p->unit, sizeof p->unit, "%s", u->name);
    /* past the top of the shade unit's widths: the scene's render and
     * --compare say so and stop (exit 2, as run and verilog do); a
     * sweep's point keeps its render without the pipelines, as a unit
     * sweep's row there says "not buildable" */
    unit_cfg wc;
    char msg[400];
    unit_cfg_default(u, &wc);
    wc.width = width;
    if (tb_width_refuse(u, &wc, msg, sizeof msg)) {
        snprintf(p->why, sizeof p->why, "not buildable at width %d: %s", width, msg);
        if (which != TB_PIPES_BOTH) return TB_OK;
        snprintf(err, errlen, "width %d (both pipelines in hardware): %s", width, msg);
        return TB_BADINPUT;
    }
    double fr[FRAME_MAX];
    int nfr = frame(d, v, fr);
    p->n = is_cook(u) ? d->mat.dg : shade_n(u, d->mat.shininess);
    for (int k = 0; k < u->nsched && p->nrows + 2 <= TB_PIPES_MAX; k++) {
        shader s;
        if (shader_at(d, width, k, &s, err, errlen)) return TB_BADINPUT;
        int rc = TB_OK;
        if (which & TB_PIPES_REF)
            rc = ref_row(r, rec, &s, fr, nfr, o->jobs < 1 ? 1 : o->jobs, &p->row[p->nrows++], k ? NULL : &p->ref_hw,
                         err, errlen);
        if (rc == TB_OK && (which & TB_PIPES_METHOD))
            rc = method_row(d, m, g, o, r, rec, &s, fr, nfr, &p->row[p->nrows++], k ? NULL : &p->hw_nodes, err, errlen);
        if (rc != TB_OK) { tb_scene_pipes_free(p); return rc; }
    }
    p->ok = 1;
    return TB_OK;
}

void tb_scene_pipes_free(tb_scene_pipes *p)
{
    free(p->ref_hw);
    free(p->hw_nodes);
    p->ref_hw = p->hw_nodes = NULL;
}

const tb_pipe_row *tb_scene_pipes_ref(const tb_scene_pipes *p, const char *sched)
{
    for (int i = 0; p && i < p->nrows; i++)
        if (!p->row[i].method && !strcmp(p->row[i].sched, sched)) return &p->row[i];
    return NULL;
}

int tb_scene_render_pipes(const scn_desc *d, const scn_mesh *m, const scn_gbuf *g, const tb_scene_opts *o,
                          int which, tb_scene_result *r, tb_scene_pipes *p, char *err, size_t errlen)
{
    tb_scene_nodes rec;
    memset(&rec, 0, sizeof rec);
    memset(p, 0, sizeof *p);
    tb_scene_opts o1 = *o;
    o1.nodes = &rec;
    int rc = render_of(d, m, g, &o1, r, err, errlen);
    if (rc == TB_OK && tb_scene_speed_of(r, r->cfg.width, err, errlen)) {
        tb_scene_free(r);
        rc = TB_FAIL;
    }
    if (rc == TB_OK) {
        rc = tb_scene_pipes_run(d, m, g, o, r, &rec, r->cfg.width, which, p, err, errlen);
        if (rc != TB_OK) tb_scene_free(r);
        else r->pipes = p;
    }
    tb_scene_nodes_free(&rec);
    return rc;
}

int tb_scene_pipes_refs(const scn_desc *d, const scn_mesh *m, const scn_gbuf *g, const tb_scene_opts *o,
                        const int *widths, int nw, tb_pipe_row *rows, int *nrows, char *err, size_t errlen)
{
    *nrows = 0;
    tb_scene_nodes rec;
    memset(&rec, 0, sizeof rec);
    tb_scene_result r;
    tb_scene_opts o1 = *o;
    o1.nodes = &rec;
    o1.energy = 0;
    const scn_view *v = &d->view;
    char why[200];
    if (!tb_scene_pipes_fit(d, v, why, sizeof why)) return TB_OK;
    int rc = render_of(d, m, g, &o1, &r, err, errlen), rendered = rc == TB_OK;
    double fr[FRAME_MAX];
    int nfr = frame(d, v, fr);
    const unit_desc *u = shade_unit(d);
    for (int w = 0; rc == TB_OK && w < nw; w++)
        for (int k = 0; rc == TB_OK && k < u->nsched; k++) {
            shader s;
            if (shader_at(d, widths[w], k, &s, err, errlen)) rc = TB_BADINPUT;
            else rc = ref_row(&r, &rec, &s, fr, nfr, o->jobs < 1 ? 1 : o->jobs, &rows[(*nrows)++], NULL, err, errlen);
        }
    if (rendered) tb_scene_free(&r);
    tb_scene_nodes_free(&rec);
    return rc;
}

/* ------------------------------------------------------------ output */

void tb_scene_pipes_print(FILE *f, const tb_scene_pipes *p)
{
    if (!p) return;
    if (!p->ok) {
        fprintf(f, "  %-22s %s\n", "both pipelines", p->why);
        return;
    }
    fprintf(f, "  both pipelines in hardware: unit %s (width %d, %s %d) per pixel (per-pixel), and shading the "
            "method's nodes (node+span)\n", p->unit, p->width, strcmp(p->unit, "shade") ? "g" : "n", p->n);
    fprintf(f, "    %-10s %-9s %5s %11s %10s %9s %9s %8s %10s %9s %7s\n", "side", "schedule", "spans", "NMSE",
            "clocks/px", "area GE", "f_max", "Mpx/s", "Mpx/s/kGE", "GE/Mpx/s", "pJ/px");
    for (int i = 0; i < p->nrows; i++) {
        const tb_pipe_row *w = &p->row[i];
        char a[32];
        if (isfinite(w->nmse)) snprintf(a, sizeof a, "%.3e", w->nmse);
        else snprintf(a, sizeof a, "inf");
        char k[16] = "-";
        if (w->method) snprintf(k, sizeof k, "%d", w->spans);
        fprintf(f, "    %-10s %-9s %5s %11s %10.3f %9.0f %5.0f MHz %8.4g %10.4g %9.4g %7.3g\n",
                w->method ? "node+span" : "per-pixel", w->sched, k, a, w->clocks_per_pixel, w->area_ge, w->fmax_mhz,
                w->pixels_per_s / 1e6, w->pps_per_kge / 1e6, w->ge_per_mpps, w->pj_per_pixel);
    }
    for (int i = 0; i < p->nrows; i++) {
        const tb_pipe_row *w = &p->row[i], *ref = tb_scene_pipes_ref(p, w->sched);
        if (!w->method || !ref) continue;
        fprintf(f, "    %s: the method %.3gx the reference's pixels/s per kGE (%.3gx its area at equal pixels/s), "
                "%.3gx its energy per pixel\n", w->sched, w->pps_per_kge / ref->pps_per_kge,
                w->ge_per_mpps / ref->ge_per_mpps, w->pj_per_pixel / ref->pj_per_pixel);
    }
}

static void row_json(FILE *f, const tb_pipe_row *w)
{
    fprintf(f, "{\"side\": \"%s\", \"schedule\": ", w->method ? "method" : "reference");
    base_json_str(f, w->sched);
    struct { const char *k; double v; } t[] = {
        { "nmse", w->nmse }, { "clocks_per_pixel", w->clocks_per_pixel }, { "area_ge", w->area_ge },
        { "fmax_mhz", w->fmax_mhz }, { "pixels_per_s", w->pixels_per_s }, { "pixels_per_s_per_kge", w->pps_per_kge },
        { "ge_per_mpixels_per_s", w->ge_per_mpps }, { "energy_pj_per_pixel", w->pj_per_pixel },
        { "shade_clocks_per_item", w->shade_cpi }, { "shade_area_ge", w->shade_area },
        { "shade_fmax_mhz", w->shade_fmax }, { "shade_energy_pj_per_item", w->shade_pj },
        { "nodes_per_pixel", w->nodes_per_pixel }, { "span_units", w->spans }, { "span_clocks_per_pixel", w->span_cpp },
        { "span_area_ge", w->span_area }, { "span_fmax_mhz", w->span_fmax }, { "span_energy_pj_per_pixel", w->span_pj },
    };
    for (size_t k = 0; k < sizeof t / sizeof t[0]; k++) {
        if (!w->method && k >= 12) break;          /* the span unit's parts: the method's */
        fprintf(f, ", \"%s\": ", t[k].k);
        base_json_num(f, t[k].v, 17);
    }
    fprintf(f, ", \"overflows\": %llu}", (unsigned long long)w->overflows);
}

void tb_scene_pipes_json(FILE *f, const tb_scene_pipes *p)
{
    if (!p) return;
    fputs(",\n  \"pipelines\": {\"unit\": ", f);
    base_json_str(f, p->ok ? p->unit : "shade");
    fputs(", ", f);
    if (!p->ok) {
        fputs("\"available\": false, \"why\": ", f);
        base_json_str(f, p->why);
        fputs("}", f);
        return;
    }
    fprintf(f, "\"available\": true, \"width\": %d, \"n\": %d, \"rows\": [", p->width, p->n);
    for (int i = 0; i < p->nrows; i++) {
        fputs(i ? ",\n    " : "\n    ", f);
        row_json(f, &p->row[i]);
    }
    fputs("]}", f);
}
