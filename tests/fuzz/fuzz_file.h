/* fuzz_file.h - libFuzzer harnesses for readers that take a path: the
 * input goes to a scratch file of this process, the reader reads it. */
#ifndef FUZZ_FILE_H
#define FUZZ_FILE_H
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* The scratch file's path (one per process and suffix, removed at exit). */
static char fuzz_path[128];
static void fuzz_cleanup(void) { if (fuzz_path[0]) unlink(fuzz_path); }

static const char *fuzz_file(const uint8_t *data, size_t size, const char *suffix)
{
    if (!fuzz_path[0]) {
        const char *tmp = getenv("TMPDIR");
        snprintf(fuzz_path, sizeof fuzz_path, "%s/shadesim_fuzz.%ld%s", tmp && *tmp ? tmp : "/tmp",
                 (long)getpid(), suffix);
        atexit(fuzz_cleanup);
    }
    FILE *f = fopen(fuzz_path, "wb");
    if (!f) abort();
    if (size && fwrite(data, 1, size, f) != size) abort();
    if (fclose(f)) abort();
    return fuzz_path;
}
#endif
