/* tb_scene_pipes.h - a scene through both pipelines in hardware: the
 * per-pixel reference on the `shade` unit, and the method with its nodes
 * shaded on the same unit before the span unit interpolates them
 * (docs/scenes.md, "Both pipelines in hardware").
 *
 * A render that recorded its pixels' and nodes' normals (tb_scene_opts
 * .nodes) hands them over: every covered pixel's normal as interpolated
 * goes through the shade unit (the hardware reference image), every node's
 * too (node intensities from hardware), and the scene is rendered again
 * with those node intensities replayed into the span unit. For each of the
 * shade unit's schedules, both sides measured against the float image:
 *
 *   reference  the shade unit alone: its clocks per pixel, area, f_max and
 *              energy per pixel, simulated over every covered pixel;
 *   method     a node shader feeding k span units, side by side at one
 *              clock (the slower f_max of the two units): clocks per
 *              pixel = max(span unit's / k, shade's clocks per item x
 *              nodes per pixel), area shade + k span units, k (1 to
 *              TB_PIPES_KMAX) the one with the most pixels per second per
 *              kGE; energy per pixel the span unit's plus the shade
 *              unit's per node x nodes per pixel (the idle clocks of the
 *              unit that waits not counted: a gated clock).
 *
 * pixels/s = f_max / clocks per pixel; per kGE = pixels/s / (area / 1000)
 * (pixels per second at equal area); the area at equal pixels per second
 * is its inverse (GE per M pixels/s), energy per pixel does not change
 * with the number of copies. */
#ifndef TB_SCENE_PIPES_H
#define TB_SCENE_PIPES_H
#include "testbench/study/tb_scene.h"

/* One side of the comparison at one schedule of the shade unit. */
typedef struct tb_pipe_row {
    int    method;                 /* 0: the per-pixel reference; 1: the method */
    char   sched[16];              /* the shade unit's schedule */
    int    width;                  /* the shade unit's width */
    double nmse;                   /* against the float reference image */
    uint64_t overflows;            /* the shade unit's (inputs too) and, method, the span unit's */
    double clocks_per_pixel, area_ge, fmax_mhz, pixels_per_s, pps_per_kge, ge_per_mpps, pj_per_pixel;
    /* the parts */
    double shade_cpi, shade_area, shade_fmax, shade_pj;   /* per item */
    double nodes_per_pixel;        /* method */
    int    spans;                  /* method: span units fed by the node shader */
    double span_cpp, span_area, span_fmax, span_pj;       /* method: the span unit's */
} tb_pipe_row;

#define TB_PIPES_MAX (2 * UNIT_MAX_SCHED)
#define TB_PIPES_KMAX 64
typedef struct tb_scene_pipes {
    int    ok;                     /* 0: no comparison, why says why */
    char   why[480];
    char   unit[16];               /* shade or shade_cook */
    int    width, n;               /* the shade unit's width; the shininess (shade) or g (shade_cook) */
    int    nrows;                  /* reference then method, schedule by schedule */
    tb_pipe_row row[TB_PIPES_MAX];
    int    w, h;
    double *ref_hw;                /* [w*h] the reference through the shade unit (first schedule) */
    double *hw_nodes;              /* [w*h] the method with nodes from it (first schedule) */
} tb_scene_pipes;

/* 1 if a shade unit computes d's lighting in view v (one directional
 * light, an orthographic camera; shade: Blinn or no specular term, a
 * whole shininess in the unit's range; shade_cook: Cook-Torrance with
 * D_g, its roughness in the unit's range, the light within 120 degrees of
 * the view), else 0 and why. */
int  tb_scene_pipes_fit(const scn_desc *d, const scn_view *v, char *why, size_t len);
/* Both pipelines for render r of d (mesh m, or surface buffer g when not
 * NULL), which recorded into rec with options o; the shade unit at
 * `width`; which: TB_PIPES_REF and / or TB_PIPES_METHOD, the rows made.
 * rec is replayed (and left so). Fills p (p->ok 0 with why when the
 * lighting does not fit or there is no shade unit); TB_OK, or TB_FAIL /
 * TB_BADINPUT with a message. */
enum { TB_PIPES_REF = 1, TB_PIPES_METHOD = 2, TB_PIPES_BOTH = 3 };
int  tb_scene_pipes_run(const scn_desc *d, const scn_mesh *m, const scn_gbuf *g, const tb_scene_opts *o,
                        const tb_scene_result *r, tb_scene_nodes *rec, int width, int which, tb_scene_pipes *p,
                        char *err, size_t errlen);
/* The reference alone at each of nw widths and every schedule of the
 * shade unit, into rows (room for nw x its schedules), *nrows of them (0
 * when the lighting does not fit): a sweep's shader configurations. */
int  tb_scene_pipes_refs(const scn_desc *d, const scn_mesh *m, const scn_gbuf *g, const tb_scene_opts *o,
                         const int *widths, int nw, tb_pipe_row *rows, int *nrows, char *err, size_t errlen);
void tb_scene_pipes_free(tb_scene_pipes *p);
/* The unit that shades d per pixel (shade or shade_cook), or NULL when
 * none computes d's lighting. */
const unit_desc *tb_scene_pipes_unit(const scn_desc *d);
/* The method's row over the reference's at one schedule (NULL: none). */
const tb_pipe_row *tb_scene_pipes_ref(const tb_scene_pipes *p, const char *sched);
/* The table's lines (after the render's), and scene.json's member
 * "pipelines" (after a comma). */
void tb_scene_pipes_print(FILE *f, const tb_scene_pipes *p);
void tb_scene_pipes_json(FILE *f, const tb_scene_pipes *p);
/* The render with the pipelines in one call: the render (of m, or on g)
 * recording, tb_scene_speed_of, tb_scene_pipes_run at the scene's width. The result's
 * pipes points at p. TB_OK, or TB_FAIL / TB_BADINPUT with a message. */
int  tb_scene_render_pipes(const scn_desc *d, const scn_mesh *m, const scn_gbuf *g, const tb_scene_opts *o,
                           int which, tb_scene_result *r, tb_scene_pipes *p, char *err, size_t errlen);
#endif
