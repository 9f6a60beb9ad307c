/* fuzz_vec.c - the vector file reader (vec_file_read) on any bytes: it
 * returns 0 or -1 with a message, and never crashes or leaks. */
#include "tests/fuzz/fuzz_file.h"
#include "vectors/vec_file.h"
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *path = fuzz_file(data, size, ".vec");
    vec_set s;
    char err[512];
    memset(&s, 0, sizeof s);
    if (vec_file_read(path, &s, NULL, err, sizeof err) == 0) vec_set_free(&s);
    else if (!err[0]) abort();          /* a refusal always says why */
    /* The streamed reader gives the same verdict a block at a time. */
    vec_stream *v = vec_stream_open(path, NULL, err, sizeof err);
    if (v) {
        const vec_set *rows;
        while (vec_stream_next(v, &rows) == 1) {}
        vec_stream_close(v);
    }
    return 0;
}
