/* base_mem.h - memory that is about to be written, paged in at once.
 *
 * A page of a fresh allocation is made on its first write, one fault per
 * 4 KiB; on a virtual machine each fault costs microseconds (200,000
 * horner3 items streamed took 2,900 of them, about a tenth of the run's
 * CPU time). Buffers that a run fills right away and uses again (a
 * stream's waves and rows) are paged in with one call instead.
 */
#ifndef BASE_MEM_H
#define BASE_MEM_H
#include <stddef.h>

/* The whole pages of [p, p + n) paged in for writing, where the system
 * can (Linux 5.14 and later); else nothing: the first writes page them
 * in as before. The contents are kept. */
void base_mem_populate(void *p, size_t n);
#endif
