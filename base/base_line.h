/* base_line.h - one text line at a time, with a bound: every line reader
 * of the program (scene files, OBJ meshes) reads through it, so that a
 * stream with no newline (/dev/zero, a binary file) costs at most one
 * line's worth of memory and time before it is refused. Whole files
 * (sweep CSVs for merge and chart) are read by base_text_read, with the
 * same bound on a line.
 */
#ifndef BASE_LINE_H
#define BASE_LINE_H
#include <stdio.h>
#include <stddef.h>

enum {
    BASE_LINE_EOF  = -1,    /* end of file, nothing read */
    BASE_LINE_LONG = -2,    /* more than max bytes before the LF */
    BASE_LINE_NUL  = -3,    /* a NUL byte: not a text file */
    BASE_LINE_ERR  = -4     /* a read error (errno set) */
};

/* One line of f into buf (room for max + 1 bytes), without its LF and
 * NUL-terminated: its length, or one of the codes above. The reading
 * stops at the first NUL byte or when the line passes max bytes: at most
 * max + 1 bytes are read, the rest of the stream is left unread. A last
 * line without a LF is a line. */
long base_line_read(FILE *f, char *buf, size_t max);

/* A whole text file ("-": standard input) in memory, NUL-terminated;
 * *len its length. Checked as it is read, so that a device or a huge
 * binary is refused at its first bad block instead of being held: a NUL
 * byte ("PATH:LINE: not a text file (NUL byte)") or a line over max_line
 * bytes ("PATH:LINE: line longer than N bytes") stops the reading: memory follows the
 * file read so far, and a line without end stops within about twice
 * max_line. NULL with the message. */
char *base_text_read(const char *path, size_t max_line, size_t *len, char *err, size_t errlen);
#endif
