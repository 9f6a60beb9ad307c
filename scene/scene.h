/* scene.h - scenes to shade: meshes, cameras, lights, materials, the
 * scene description file, scanline rasterization into a per-pixel surface
 * buffer, the double-precision reference shading, spans, and PNG images.
 *
 * This layer knows nothing of the simulator or of hardware units:
 * testbench/tb_scene.c composes it with units/ to shade a scene through
 * the simulated interpolation hardware. Prefix: scn_.
 *
 * Files of the layer, one job each:
 *   scene_mesh.c    meshes, built-in procedural face / sphere / torus
 *   scene_obj.c     Wavefront OBJ reader
 *   scene_raster.c  cameras, scanline rasterizer with z-buffer -> scn_gbuf
 *   scene_span.c    spans of a surface buffer and attributes along them
 *   scene_shade.c   reference shading (lights, materials, BRDF models)
 *   scene_file.c    the scene description format (key value lines): reading it
 *   scene_desc.c    a description's defaults, built-in scenes, held-out view, writing
 *   scene_png.c     PNG encoder (filters, zlib stream, CRC-32), colour maps
 *   scene_deflate.c DEFLATE compressor (LZ77 + Huffman) for the PNGs
 */
#ifndef SCENE_H
#define SCENE_H
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#define SCN_MAX_LIGHTS  4
#define SCN_MAX_REGIONS 16

/* ------------------------------------------------------------- meshes */

/* An indexed triangle mesh with a unit normal per vertex and a region
 * label per triangle (0 = no particular region). Counter-clockwise
 * triangles, seen from outside, face outwards. */
typedef struct scn_mesh {
    size_t    nv, nt;
    double  (*pos)[3];
    double  (*nrm)[3];
    uint32_t (*tri)[3];
    uint8_t  *region;            /* [nt] */
    int       nregions;          /* labels 0..nregions-1 are used */
    const char *region_name[SCN_MAX_REGIONS];   /* static strings */
    size_t    ignored;           /* OBJ: lines of other kinds ignored (vt, usemtl, ...) */
} scn_mesh;

/* Built-in procedural meshes by name: "face", "sphere", "torus". detail
 * scales the tessellation (1 = default). 0, or -1 with a message. */
int  scn_mesh_builtin(const char *name, int detail, scn_mesh *m, char *err, size_t errlen);
/* Names of the built-ins, NULL-terminated. */
extern const char *const scn_mesh_builtin_names[];
/* Read an OBJ file (v, vn, f; polygons fan-triangulated; negative indices;
 * normals computed from faces where missing). Errors: "FILE:LINE: what".
 * 0, or -1 with a message. */
int  scn_mesh_obj(const char *path, scn_mesh *m, char *err, size_t errlen);
void scn_mesh_free(scn_mesh *m);

/* ------------------------------------------------- camera, lights, view */

typedef struct scn_camera {
    int    perspective;          /* 0: orthographic */
    double eye[3], target[3], up[3];
    double fov_deg;              /* perspective: vertical field of view */
    double ortho_height;         /* orthographic: world height of the image */
} scn_camera;

typedef struct scn_light {
    int    point;                /* 0: directional */
    double v[3];                 /* directional: direction *towards* the light; point: position */
    double intensity;            /* I0 */
} scn_light;

/* What can change between two renders of the same scene: the camera and
 * the lights (the held-out view of a format search is another view). */
typedef struct scn_view {
    scn_camera cam;
    int        nlights;
    scn_light  light[SCN_MAX_LIGHTS];
} scn_view;

/* ------------------------------------------------------------ material */

typedef enum {
    SCN_SPEC_PHONG,              /* ks (R.V)^n */
    SCN_SPEC_BLINN,              /* ks (N.H)^n */
    SCN_SPEC_COOK,               /* ks F D G / (pi (N.L)(N.V)), D Beckmann or D4/D8/D16 (scene_shade.c) */
    SCN_SPEC_WARD,               /* ks e / (4 pi a^2 sqrt((N.L)(N.V))), e exact or the 16th-power polynomial */
    SCN_SPEC__COUNT
} scn_spec_model;

typedef enum { SCN_FRESNEL_NONE, SCN_FRESNEL_SCHLICK, SCN_FRESNEL_MSCHLICK } scn_fresnel;

typedef struct scn_material {
    double ambient, kd, ks;
    double shininess;            /* Phong / Blinn exponent n */
    scn_spec_model spec;
    int    dg;                   /* Cook: 0 = exact Beckmann, 4/8/16 = D_g; Ward: 0 exact, 16 polynomial */
    double m;                    /* Cook roughness */
    double alpha;                /* Ward roughness */
    scn_fresnel fresnel;
    double fresnel_n;            /* exponent n of Schlick / modified Schlick */
} scn_material;

/* ---------------------------------------------- the scene description */

typedef enum { SCN_POL_LINEAR, SCN_POL_QUADRATIC, SCN_POL_CUBIC_N1, SCN_POL_CUBIC_N2,
               SCN_POL_ADAPTIVE_REGION, SCN_POL_ADAPTIVE_AUTO, SCN_POL__COUNT } scn_policy;

#define SCN_MAX_FMT 64

/* Operations counted per pixel for the reference and for the method, and
 * their cost weights (scene key "cost", e.g. "cost div=8"). */
typedef enum { SCN_OP_ADD, SCN_OP_MUL, SCN_OP_DIV, SCN_OP_SQRT, SCN_OP_POW, SCN_OP__COUNT } scn_op;
extern const char *const scn_op_name[SCN_OP__COUNT];     /* "add" "mul" "div" "sqrt" "pow" */

/* Everything a scene file says. Every field has a default
 * (scn_desc_default: the face scene) but the hardware's, whose defaults
 * are the unit's ("" here). Strings are owned by the struct. */
#define SCN_DESC_NKEYS  40       /* room for the keys of scn_desc_keys */
typedef struct scn_desc {
    int          version;        /* "shadesim-scene 1" */
    char         mesh[256];      /* built-in name or OBJ path (relative to the file) */
    int          detail;
    int          width, height;  /* resolution */
    scn_view     view;
    scn_view     heldout;        /* the view a format search does not see */
    scn_material mat;
    scn_policy   policy;
    uint8_t      region_deg[SCN_MAX_REGIONS];   /* adaptive-region: degree per region (2 or 3) */
    int          auto_cubic_nodes;              /* adaptive-auto: 1 = N1, 2 = N2 */
    double       auto_threshold;                /* adaptive-auto: degree 3 when the curvature measure exceeds it */
    /* The hardware: the policy's unit's configuration, kept as the scene
     * file or --set wrote it ("": not set). L, terms, series and schedule
     * are the unit's parameters, whose ranges, choices and defaults are
     * its descriptor's alone; width, round and overflow are every unit's
     * settings (unit_cfg_default's defaults, the simulator's mode names).
     * testbench/study/tb_scene_cfg.c applies what is set over the unit's
     * defaults through its setters (and refuses what they refuse), and
     * the render reads the configuration that gives. */
    char         L[16], terms[16];   /* a whole number (the file checks that much) */
    char         series[16];     /* a choice name: "paper", "quarter" */
    char         schedule[16];   /* a schedule name: "paper", "mac", "pipe" */
    char         unit[256];      /* a datapath file in place of the policy's unit ("": none) */
    char         fmt_width[16];  /* W of the default-format rule: a whole number 4..64 */
    int          nfmt;
    char         fmt[SCN_MAX_FMT][48];   /* NAME=sI.F overrides, in order */
    char         rnd[16], ovf[16];   /* mode names: "trunc", "half-up", "even"; "wrap", "sat" */
    double       cost[SCN_OP__COUNT];           /* weights of the operation count */
    /* Bookkeeping of scn_desc_set / scn_desc_read (scene_file.c): */
    int          cook_dg, ward_dg;   /* "distribution" and "ward-form" as set; mat.dg is the
                                        one of mat.spec (so key order does not matter) */
    unsigned     heldout_given;      /* SCN_HELD_* bits: held-out keys set explicitly; the
                                        others follow the view (scn_desc_sync) */
    /* Where each key was last set, for errors found after reading (a
     * missing mesh, a camera or formats that cannot work): */
    char         src[256];           /* the scene file read ("" none; cut if longer) */
    int          key_line[SCN_DESC_NKEYS];   /* its line in src; SCN_LINE_SET: by
                                        scn_desc_set (--set), after every line; 0: default */
} scn_desc;

#define SCN_LINE_SET    0x7fffffff
#define SCN_HELD_EYE    1u
#define SCN_HELD_TARGET 2u
#define SCN_HELD_LIGHT  4u

void scn_desc_default(scn_desc *d);
/* Read a scene file over the defaults (d is set to scn_desc_default
 * first; on error it is left unchanged). Errors: "FILE:LINE: what". 0 or -1. */
int  scn_desc_read(const char *path, scn_desc *d, char *err, size_t errlen);
/* Set one key from text, as a line "key value" would ("light" appends a
 * light); for --set KEY=VALUE on the command line. 0 or -1 with a message. */
int  scn_desc_set(scn_desc *d, const char *key, const char *value, char *err, size_t errlen);
/* Write the description back as a scene file (every key; the hardware's
 * only where set, so that the unit's defaults stay the unit's). */
int  scn_desc_write(FILE *f, const scn_desc *d);
const char *scn_policy_name(scn_policy p);
/* The built-in scenes "face" (= scn_desc_default), "sphere", "torus": the
 * face scene's settings on that mesh with a camera that frames it. 0, or
 * -1 for an unknown name. Names NULL-terminated in scn_desc_builtin_names. */
int  scn_desc_builtin(const char *name, scn_desc *d);
extern const char *const scn_desc_builtin_names[];
/* After changing view fields directly: recompute what follows the view
 * (held-out camera type, up, fov, height always; held-out eye, target,
 * lights unless set explicitly). scn_desc_set and scn_desc_read call it. */
void scn_desc_sync(scn_desc *d);
/* The prefix of an error in a value that keys (NULL-terminated) set:
 * "FILE:LINE: " of the one set last, "--set KEY: " when that was
 * scn_desc_set, "" when all are defaults. Returns buf. */
const char *scn_desc_where(const scn_desc *d, const char *const *keys, char *buf, size_t len);
/* The view's and the held-out view's cameras can be drawn with (up not
 * along the view direction, ...): 0, or -1 with "WHERE: camera: what",
 * WHERE the line of the camera key set last. */
int  scn_desc_check_camera(const scn_desc *d, char *err, size_t errlen);
/* The scene file keys, NULL-terminated (for help texts). */
extern const char *const scn_desc_keys[];

/* ---------------------------------------------------- surface buffer */

/* Per pixel: what the rasterizer left after the z-test. Pixel (x, y) has
 * its centre at (x + 0.5, y + 0.5); y = 0 is the top row. */
typedef struct scn_gbuf {
    int       w, h;
    int32_t  *tri;               /* triangle index, -1 where uncovered */
    uint8_t  *region;
    double   *depth;             /* view-space depth (smaller is nearer) */
    double  (*pos)[3];           /* world position */
    double  (*nrm)[3];           /* interpolated vertex normal, not normalized */
    uint32_t *frags;             /* fragments that passed the coverage test (before z) */
    /* World size of one pixel at depth z: foot0 + foot1 * z (orthographic:
     * foot1 = 0; perspective: foot0 = 0). scn_spans uses it to tell a
     * depth jump; a gbuf built by hand may leave both 0 (scene_span.c). */
    double    foot0, foot1;
} scn_gbuf;

/* Rasterize with a z-buffer, back faces culled, the top-left fill rule
 * (a pixel centre on a shared edge belongs to exactly one triangle).
 * Attributes are interpolated perspective-correctly. 0, or -1 with a
 * message (a camera it cannot use); out of memory ends the program. */
/* The checks scn_raster makes of a camera, alone: 0, or -1 with
 * "camera: what". */
int  scn_camera_check(const scn_camera *c, char *err, size_t errlen);
int  scn_raster(const scn_mesh *m, const scn_camera *cam, int w, int h, scn_gbuf *g,
                char *err, size_t errlen);
void scn_gbuf_free(scn_gbuf *g);

/* ----------------------------------------------------------- spans */

/* A span: a maximal run x0..x1-1 of covered pixels on row y, broken where
 * the region label changes or the surface jumps in depth (a silhouette
 * over another part of the mesh). */
typedef struct scn_span { int y, x0, x1; uint8_t region; } scn_span;

/* All spans, rows top to bottom, left to right. *out is malloc'ed. */
size_t scn_spans(const scn_gbuf *g, scn_span **out);
/* Position and normal (normalized) at fractional pixel x in [x0, x1-1] of
 * a span: linear interpolation between the two neighbouring pixels. */
void   scn_span_at(const scn_gbuf *g, const scn_span *s, double x, double pos[3], double nrm[3]);

/* ---------------------------------------------------------- shading */

/* Reference intensity at a surface point (unit normal nrm) seen from the
 * view's camera: ambient + sum over lights of I0 (kd max(0, N.L) + ks
 * spec), clamped to [0, 1]. Counts nothing; pure function. */
double scn_shade(const scn_material *mat, const scn_view *v, const double pos[3], const double nrm[3]);

/* ----------------------------------------------------------- images */

/* Encode an 8-bit image (channels 1 = grey, 3 = RGB) as PNG in memory:
 * a filter per row, compressed by scn_deflate (level 1). The same pixels
 * give the same bytes. *out is malloc'ed. 0, or -1 (out of memory). */
int  scn_png_encode(int w, int h, int channels, const uint8_t *pix, uint8_t **out, size_t *len);
/* Compress in[0..n) as a raw DEFLATE stream (RFC 1951, no zlib frame):
 * level 0 codes literals only, 1 is fast (short hash chains), 2 searches
 * longer. Each block is dynamic, fixed or stored, whichever is smallest.
 * Deterministic. *out is malloc'ed. 0, or -1 (out of memory, or n of
 * 2^32 - 1 bytes or more). */
int  scn_deflate(const uint8_t *in, size_t n, int level, uint8_t **out, size_t *outlen);
/* Colour map for an error heat map: v in [0, 1] -> black, blue, red, yellow, white. */
void scn_heat_rgb(double v, uint8_t rgb[3]);
/* A distinct colour per label (region and degree maps). */
void scn_label_rgb(int label, uint8_t rgb[3]);
#endif
