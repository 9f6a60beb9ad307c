/* fuzz_obj.c - the Wavefront OBJ reader (scn_mesh_obj) on any bytes. */
#include "tests/fuzz/fuzz_file.h"
#include "scene/scene.h"
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    scn_mesh m;
    char err[512];
    memset(&m, 0, sizeof m);
    if (scn_mesh_obj(fuzz_file(data, size, ".obj"), &m, err, sizeof err) == 0) scn_mesh_free(&m);
    else if (!err[0]) abort();
    return 0;
}
