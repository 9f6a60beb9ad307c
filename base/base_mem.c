/* base_mem.c - memory paged in before it is written (base_mem.h). */
#define _DEFAULT_SOURCE   /* madvise */
#include "base/base_mem.h"
#include <stdint.h>
#include <sys/mman.h>
#include <unistd.h>

void base_mem_populate(void *p, size_t n)
{
#ifdef MADV_POPULATE_WRITE
    long page = sysconf(_SC_PAGESIZE);
    if (page <= 0) return;
    uintptr_t m = (uintptr_t)page - 1, a = ((uintptr_t)p + m) & ~m, b = ((uintptr_t)p + n) & ~m;
    /* (an older kernel says EINVAL: the writes page it in then) */
    if (b > a) (void)madvise((void *)a, b - a, MADV_POPULATE_WRITE);
#else
    (void)p; (void)n;
#endif
}
