/* tb_scene.h - a scene shaded through the simulated hardware.
 *
 * tb_scene_render composes the layers: the scene (scene/) is rasterized
 * into a surface buffer and shaded per pixel in double precision (the
 * reference image); each span is cut into intervals of L pixels whose node
 * intensities are shaded exactly (counted, not simulated) and shared
 * between neighbouring intervals; the span unit of the scene's policy
 * (units/unit_span.c, driven by tb_span_run) then interpolates every pixel
 * cycle-accurately at the scene's formats. The result holds both images,
 * the error metrics, the clocks and area of the instantiated hardware and
 * the operation counts of the reference and of the method.
 */
#ifndef TB_SCENE_H
#define TB_SCENE_H
#include "scene/scene.h"
#include "testbench/study/tb_span.h"
#include "testbench/tb.h"

#define TB_SCENE_BANDS 16

/* What a render hands the hardware shading pipelines (tb_scene_pipes.h)
 * and takes back from them, band by band: recording, each covered pixel's
 * normal as interpolated and its place in the image, and each node's
 * normal in the order the render shades the nodes (an adaptive-auto
 * interval's I(1/4) or I(3/4) node always, as its degree is not known
 * before the nodes are); replaying, the nodes' intensities in that order
 * in place of the exact ones (and the reference pixels not recorded). */
typedef struct tb_scene_nodes_band {
    double (*pn)[3];             /* covered pixels' normals */
    size_t *pix, npix, cap_pix;  /* their indices y * w + x */
    double (*nn)[3];             /* nodes' normals */
    size_t nnodes, cap_nodes;
    const double *val;           /* replay: the nodes' intensities */
    size_t next;                 /* replay: the next node's */
} tb_scene_nodes_band;
typedef struct tb_scene_nodes {
    int replay;                  /* 0: record; 1: replay */
    tb_scene_nodes_band band[TB_SCENE_BANDS];
} tb_scene_nodes;
void tb_scene_nodes_free(tb_scene_nodes *n);

typedef struct tb_scene_opts {
    int         jobs;        /* threads (rows split into bands); output identical for any value */
    int         heldout;     /* 1: render the description's held-out view instead of its view */
    const char *vcd_path;    /* NULL, or a VCD of the hardware (first band only) */
    const unit_fmts *fmts;   /* NULL: the scene's formats (width rule + fmt overrides) */
    int         no_batch;    /* 1: every band on the event-driven kernel alone; 0: bands as
                              * lanes of the batch mode (same bytes, faster) */
    int         energy;      /* 1: count the hardware's switching activity (r->hwst.toggles,
                              * r->hwst.energy_pj, r->energy_pj_per_pixel); 0: not counted,
                              * and the render pays nothing for it */
    tb_scene_nodes *nodes;   /* NULL, or record into it / replay from it (not with a prep) */
    struct tb_items_memo *memo;   /* NULL, or the shade unit's runs over the nodes kept and
                              * reused (a sweep's points that share their nodes) */
} tb_scene_opts;

/* Speed and energy of a render in hardware terms (docs/timing.md,
 * docs/scenes.md "Speed and energy"): the span unit's critical path and
 * f_max, pixels per second at it, energy per pixel (when the render
 * counted it: tb_scene_opts.energy); and for the per-pixel reference, what
 * the tool can build of it: the divider (unit div at the scene's width),
 * which bounds a per-pixel shader that divides as often as the reference
 * does from above in speed and from below in energy (its square roots and
 * powers, which no unit builds, would only add to them). */
typedef struct tb_scene_speed {
    tb_ppa   hw;                   /* the span unit: levels, crit_ps, path, fmax_mhz */
    double   pixels_per_s;         /* f_max / clocks per pixel */
    double   energy_pj_per_pixel;  /* NaN when the render did not count it */
    /* the reference's bound */
    double   ref_divs;             /* divides per covered pixel (ops_ref) */
    double   div_clocks;           /* the div unit's clocks per division */
    tb_ppa   div;                  /* its critical path, f_max, energy per division */
    double   ref_pixels_per_s_max;         /* div's divisions per second / ref_divs */
    double   ref_energy_pj_per_pixel_min;  /* div's energy per division x ref_divs */
    /* the method's shaded nodes divide too (ops_hw): on the same divider */
    double   node_divs, node_pixels_per_s_max;
} tb_scene_speed;
struct tb_scene_pipes;            /* tb_scene_pipes.h */
typedef struct tb_scene_result {
    int       w, h;
    size_t    covered;                /* pixels covered by the mesh */
    double   *ref, *hw;               /* [w*h] intensities, 0 where uncovered: ref in [0, 1],
                                       * hw as the hardware gave it (not clamped) */
    uint8_t  *deg;                    /* [w*h] degree used (1, 2, 3; 0 uncovered) */
    uint8_t  *region;                 /* [w*h] region label */
    /* Metrics over covered pixels (docs/scenes.md defines them). */
    double    nmse;                   /* sum (hw - ref)^2 / sum ref^2, raw output (the verdicts' NMSE) */
    double    nmse8;                  /* the same on the 8-bit values written to ref.png and hw.png */
    double    psnr;                   /* on 8 bits, dB */
    double    max_abs_err;
    int       max_err8;               /* max |hw8 - ref8|, 8-bit values */
    double    diff8_share;            /* share of pixels whose 8-bit value differs */
    /* The hardware. */
    const unit_desc *unit;
    unit_cfg  cfg;
    unit_fmts fmts;
    tb_span_stats hwst;
    double    clocks_per_pixel;
    double    energy_pj_per_pixel;    /* hwst.energy_pj / hwst.pixels (opts.energy; else 0) */
    size_t    spans, intervals, intervals_deg2;
    double    deg2_share;
    /* Operations per covered pixel (frame constants hoisted, both sides
     * alike: tb_scene_ops.c), their weighted costs, and the long operations
     * (div + sqrt + pow, unweighted). */
    double    ops_ref[SCN_OP__COUNT], ops_hw[SCN_OP__COUNT];
    double    cost_ref, cost_hw, speedup;   /* speedup = cost_ref / cost_hw */
    double    long_ref, long_hw, speedup_long;   /* speedup_long = long_ref / long_hw */
    size_t    nodes_shaded;
    int       heldout;                /* 1: the held-out view was rendered */
    int       have_speed;             /* speed filled (tb_scene_speed_of) */
    tb_scene_speed speed;
    /* Both pipelines in hardware (tb_scene_render_pipes; not owned): the
     * table, scene.json and the images show them; where they are
     * measured, the text leaves out the divider's bound on the reference. */
    const struct tb_scene_pipes *pipes;
    /* Where the render's time went, in CPU seconds summed over its
     * threads (each thread's own clock): cpu_sim simulating the span unit
     * (tb_span_run / the batch lanes: the unit's build and levelization,
     * the inputs' quantization, every clock); cpu_render the whole render
     * (rasterization in tb_scene_render, reference and node shading,
     * intervals, simulation, metrics, operation counts). Measured, so not
     * part of any output; bench/bench_scene.c prints them. */
    double    cpu_sim, cpu_render;
} tb_scene_result;

/* Fill r->speed for render r (the unit it instantiated) at the scene's
 * width, and set r->have_speed; the text table, --compare, --sweep and
 * scene.json show it then. 0, or -1 with a message. */
int  tb_scene_speed_of(tb_scene_result *r, int width, char *err, size_t errlen);
/* Its lines in the scene table, and its members of scene.json (each
 * after a comma; nothing without r->have_speed). */
void tb_scene_speed_print(FILE *f, const tb_scene_result *r);
void tb_scene_speed_json(FILE *f, const tb_scene_result *r);

/* The span unit and configuration a description's policy needs: the
 * unit's defaults, and over them the description's hardware keys that
 * are set, each through the unit's setter (tb_scene_cfg.c). 0, or -1 with
 * a message (a parameter's: "parameter NAME: ..."). */
int  tb_scene_cfg(const scn_desc *d, const unit_desc **u, unit_cfg *cfg, char *err, size_t errlen);
/* tb_scene_cfg and the formats: the width rule's, then the fmt keys. */
int  tb_scene_unit(const scn_desc *d, const unit_desc **u, unit_cfg *cfg, unit_fmts *f,
                   char *err, size_t errlen);
/* Render. m is the description's mesh (already loaded). TB_OK, TB_FAIL or
 * TB_BADINPUT with a message. */
int  tb_scene_render(const scn_desc *d, const scn_mesh *m, const tb_scene_opts *o,
                     tb_scene_result *r, char *err, size_t errlen);
void tb_scene_free(tb_scene_result *r);

/* The hardware path on a surface buffer made elsewhere, with a shading
 * function in place of the scene's lighting (tests drive it with a
 * synthetic intensity; fn NULL: scn_shade with the description's material
 * and the chosen view). Reference and nodes both come from fn; the
 * operation counts still describe d's lighting model. */
typedef double (*tb_scene_shader)(void *ctx, const double pos[3], const double nrm[3]);
int  tb_scene_render_gbuf(const scn_desc *d, const scn_gbuf *g, tb_scene_shader fn, void *ctx,
                          const tb_scene_opts *o, tb_scene_result *r, char *err, size_t errlen);
/* What every render of one view of a description shares whatever its
 * formats (a format search renders the same scene hundreds of times): the
 * reference image, the degree and region images, the spans, and the
 * intervals with their exactly shaded nodes. tb_scene_prep_new makes it
 * for d's view (heldout 0) or held-out view on surface buffer g (which
 * must outlive it) on `jobs` threads; TB_OK, or TB_FAIL / TB_BADINPUT with
 * a message. tb_scene_render_prep renders as tb_scene_render_gbuf(d, g,
 * NULL, NULL, o with p's view) does, to the same bytes, doing only the
 * simulation and what follows it: d may differ from p's description in
 * its width, formats, rounding, overflow, schedule and cost weights (any
 * other difference is rendered from scratch); no VCD. Several threads may
 * render from one p at once. tb_scene_prep_cpu: the CPU seconds making p
 * took. */
typedef struct tb_scene_prep tb_scene_prep;
int    tb_scene_prep_new(const scn_desc *d, const scn_gbuf *g, int heldout, int jobs, tb_scene_prep **p,
                         char *err, size_t errlen);
int    tb_scene_render_prep(const scn_desc *d, const tb_scene_prep *p, const tb_scene_opts *o,
                            tb_scene_result *r, char *err, size_t errlen);
/* tb_scene_render_prep that stops, failing (TB_FAIL, a message), as soon
 * as the render's NMSE is sure to pass max_nmse (its squared error so far
 * is over the budget, with a margin for rounding): for a caller that only
 * needs to know whether a render meets max_nmse. A render that meets it
 * runs to its end and is exact. */
int    tb_scene_render_prep_budget(const scn_desc *d, const tb_scene_prep *p, const tb_scene_opts *o,
                                   double max_nmse, tb_scene_result *r, char *err, size_t errlen);
double tb_scene_prep_cpu(const tb_scene_prep *p);
/* Renders from p of exactly d (which must fit p) with the formats given
 * (tb_scene_opts.fmts) take d's unit and configuration from p instead of
 * working out the format rule's formats, which they replace anyway. Not
 * while other threads render from p. 0, or -1 with a message. */
int    tb_scene_prep_unit(tb_scene_prep *p, const scn_desc *d, char *err, size_t errlen);
void   tb_scene_prep_free(tb_scene_prep *p);
/* 1 if d's cubic intervals use node set N2 (I(3/4)): the cubic-n2
 * policy, or an adaptive one whose auto-nodes key says n2. */
int  tb_scene_nodes_n2(const scn_desc *d);
/* v on 8 bits, round(255 clamp(v, 0, 1)), NaN as 0: the images and the
 * 8-bit figures (NMSE8, PSNR, max_err8). */
uint8_t tb_scene_to8(double v);
/* Operations of one evaluation of d's lighting model at a point of view v
 * (the per-pixel cost of the reference; each shaded node costs the same),
 * as an efficient per-pixel shader does it: what is constant over the
 * frame (L of a directional light, V of an orthographic camera, H, L.V,
 * L.H from them) is computed once per frame and not counted. */
void tb_scene_point_ops(const scn_desc *d, const scn_view *v, double ops[SCN_OP__COUNT]);
/* The long operations among counts: div + sqrt + pow. */
double tb_scene_long_ops(const double ops[SCN_OP__COUNT]);
/* Scale K of the error heat map: full white is an error of 1/K, K from
 * the ladder 1, 4, 16, ..., 4096 (the largest that shows the maximum). */
int  tb_scene_err_scale(const tb_scene_result *r);
/* Write ref.png, hw.png, err-xK.png, degree.png, region.png, their keys
 * and scene.json into dir (created if needed), as one set. 0 or -1. */
int  tb_scene_write(const scn_desc *d, const tb_scene_result *r, const char *dir,
                    char *err, size_t errlen);
/* The maps' colour keys, degree-key.svg, region-key.svg and err-key.svg
 * (the heat map's at scale K), into set in dir (tb_scene_keys.c). 0 or -1. */
typedef struct base_outset base_outset;
int  tb_scene_write_keys(base_outset *set, const char *dir, const tb_scene_result *r, int K, char *err,
                         size_t errlen);
/* One JSON object: the description's settings and every figure above. */
int  tb_scene_json(FILE *f, const scn_desc *d, const tb_scene_result *r);
#endif
