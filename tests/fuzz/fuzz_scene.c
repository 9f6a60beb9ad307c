/* fuzz_scene.c - the scene file reader (scn_desc_read) on any bytes, and
 * what it accepts written back (scn_desc_write) and read again. */
#include "tests/fuzz/fuzz_file.h"
#include "scene/scene.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static scn_desc d;
    char err[512];
    if (scn_desc_read(fuzz_file(data, size, ".scene"), &d, err, sizeof err)) {
        if (!err[0]) abort();
        return 0;
    }
    FILE *f = fopen(fuzz_path, "w");
    if (!f) abort();
    scn_desc_write(f, &d);
    if (fclose(f)) abort();
    if (scn_desc_read(fuzz_path, &d, err, sizeof err)) abort();   /* what we write, we read */
    return 0;
}
