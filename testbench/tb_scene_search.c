/* tb_scene_search.c - format search and sweeps over a scene (being built). */
#include "testbench/tb_scene_search.h"

int tb_scene_search(const scn_desc *d, const scn_mesh *m, int jobs, double target_nmse,
                    const char *outdir, int json, FILE *out, char *err, size_t errlen)
{
    (void)d; (void)m; (void)jobs; (void)target_nmse; (void)outdir; (void)json; (void)out;
    snprintf(err, errlen, "scene --target-nmse: not built yet");
    return TB_BADINPUT;
}

int tb_scene_sweep(const scn_desc *d, const scn_mesh *m, int jobs, const char *spec,
                   const char *outdir, int json, FILE *out, char *err, size_t errlen)
{
    (void)d; (void)m; (void)jobs; (void)spec; (void)outdir; (void)json; (void)out;
    snprintf(err, errlen, "scene --sweep: not built yet");
    return TB_BADINPUT;
}
