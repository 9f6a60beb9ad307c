/* scene_geom.h - helpers shared by the mesh builders of the scene layer
 * (scene_mesh.c, scene_obj.c). Not part of the public interface. */
#ifndef SCENE_GEOM_H
#define SCENE_GEOM_H
#include "scene/scene.h"

/* Zero *m and allocate nv vertices and nt triangles (regions zeroed,
 * nregions 1 named "rest"). 0, or -1 (counts too large; *m is left
 * empty). Out of memory ends the program (base_out_of_memory). */
int  scn_mesh_alloc(scn_mesh *m, size_t nv, size_t nt);

/* Area-weighted vertex normals: each vertex gets the normalized sum of the
 * unnormalized cross products (twice the areas, outward for
 * counter-clockwise triangles) of the triangles using it. A vertex whose
 * sum is zero (unused, or only degenerate or cancelling triangles) gets
 * the fallback (0, 0, 1): never a NaN. */
void scn_vertex_normals(const double (*pos)[3], size_t nv, const uint32_t (*tri)[3], size_t nt,
                        double (*nrm)[3]);

/* Normalize v in place; a zero, tiny or non-finite vector becomes the
 * fallback fb (which must be a unit vector). Returns 0 when it fell back. */
int  scn_normalize_or(double v[3], const double fb[3]);
#endif
