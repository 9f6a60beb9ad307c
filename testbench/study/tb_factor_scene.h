/* tb_factor_scene.h - the factorization paper's Fig. 1 comparison on a
 * built-in scene: the Ward specular term exact at the vertices and
 * interpolated, factorized per pixel through the simulated hf_lookup
 * unit, and exact per pixel (tb_factor_scene.c). */
#ifndef TB_FACTOR_SCENE_H
#define TB_FACTOR_SCENE_H
#include <stddef.h>
#include <stdint.h>

typedef struct tb_factor_scene_result {
    int      w, h;
    size_t   covered;        /* pixels the mesh covers */
    size_t   items;          /* of them, lit and seen: hf_lookup evaluations */
    double   nmse_vertex;    /* (a) against (c) */
    double   nmse_factor;    /* (b) against (c) */
    uint64_t clocks;         /* hf_lookup's clocks for the items */
    double   area_ge;
} tb_factor_scene_result;

/* scene: a built-in scene name (its mesh, camera, first light); L, alpha:
 * hf_lookup's map resolution and Ward roughness; width: its --width; res:
 * image side (0: the scene's). dir (or NULL): vertex.png, factorized.png,
 * exact.png, grey, full white = the exact image's largest value.
 * 0, or -1 with a message. */
int tb_factor_scene(const char *scene, int L, double alpha, int width, int res, const char *dir,
                    tb_factor_scene_result *r, char *err, size_t errlen);
#endif
