/* scene_names.h - the names the scene file format gives its choices,
 * shared by its reader (scene_file.c) and its writer (scene_desc.c).
 * Internal to scene/. Each list is NULL-terminated, its index the value
 * the description stores (distribution: the index of D_g in 0, 4, 8, 16).
 */
#ifndef SCENE_NAMES_H
#define SCENE_NAMES_H
#include "scene/scene.h"

extern const char *const scn_policy_names[SCN_POL__COUNT + 1];
extern const char *const scn_spec_names[SCN_SPEC__COUNT + 1];
extern const char *const scn_dist_names[];
extern const char *const scn_fresnel_names[];
extern const char *const scn_camera_names[];
#endif
