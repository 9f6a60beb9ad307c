/* test_stream.c - tb_run_stream (a vector file read a block at a time)
 * gives the same report as tb_run (every vector in memory): the JSON
 * report and the --out rows, byte for byte, for every unit on its
 * checked-in vectors and for horner3 on a file of several blocks (more
 * items than the ring holds); so does tb_run_stream_lanes (the lanes, a
 * wave at a time, on 2 threads) but for the JSON's "sim" line, where the
 * lanes take the stream (a unit they do not take must hand the stream
 * back unread); a bad row past the first block is the reader's message,
 * as a whole read gives it. */
#include "tests/tst.h"
#include "testbench/tb.h"
#include "testbench/tb_stream.h"
#include "vectors/vec_file.h"
#include <unistd.h>

typedef struct membuf { char *p; size_t n; FILE *f; } membuf;

static void row_cb(void *data, const tb_result *r, size_t idx, uint64_t cycle, const int64_t *raw,
                   const double *expected)
{
    tb_csv_row(((membuf *)data)->f, r, idx, cycle, raw, expected);
}

static char *slurp(const char *path, size_t *n)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    long len = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *b = malloc((size_t)len + 1);
    *n = b ? fread(b, 1, (size_t)len, f) : 0;
    fclose(f);
    return b;
}

/* The JSON without its "sim" line (the engine's own). */
static void drop_sim(membuf *j)
{
    char *at = j->p ? strstr(j->p, "  \"sim\": ") : NULL;
    if (!at) return;
    char *end = strchr(at, '\n');
    end = end ? end + 1 : j->p + j->n;
    memmove(at, end, (size_t)(j->p + j->n - end) + 1);
    j->n -= (size_t)(end - at);
}

/* tb_run_stream_lanes on path against tb_run's JSON and rows (j1, c1). */
static void same_on_lanes(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fm, const char *path,
                          const vec_set *hdr, membuf *j1, const char *c1, size_t n1, const char *tag)
{
    char err[600];
    vec_stream *st = vec_stream_open(path, hdr, err, sizeof err);
    TST_CHECK(st != NULL, "%s", err);
    if (!st) return;
    membuf j3 = { 0 }, c3 = { 0 };
    c3.f = open_memstream(&c3.p, &c3.n);
    tb_csv_header(c3.f, hdr->n_out, (const char (*)[16])hdr->out_names);
    tb_result r3;
    int rewound = 0;
    int t3 = tb_run_stream_lanes(u, cfg, fm, st, row_cb, &c3, 2, &r3, &rewound, err, sizeof err);
    fclose(c3.f);
    if (t3 == TB_STREAM_KERNEL) {
        const vec_set *rows;
        TST_CHECK(rewound && vec_stream_next(st, &rows) == 1 && rows->n_rows > 0, "%s: not on lanes (%s), and not handed back",
                  tag, r3.engine_why);
    } else {
        TST_CHECK(t3 == TB_OK, "%s: lanes: %s", tag, err);
        j3.f = open_memstream(&j3.p, &j3.n);
        if (t3 == TB_OK) tb_write_json(j3.f, &r3);
        fclose(j3.f);
        membuf k = *j1;
        k.p = malloc(j1->n + 1);
        if (k.p) memcpy(k.p, j1->p, j1->n + 1);
        drop_sim(&k);
        drop_sim(&j3);
        int same = t3 == TB_OK && r3.lanes > 0 && k.p && j3.p && k.n == j3.n && !memcmp(k.p, j3.p, k.n) && c1 && n1 == c3.n
                   && !memcmp(c1, c3.p, n1);
        TST_CHECK(same, "%s: on lanes, JSON %zu/%zu bytes, CSV %zu/%zu bytes differ", tag, k.n, j3.n, n1, c3.n);
        free(k.p);
    }
    tb_result_free(&r3);
    free(j3.p); free(c3.p);
    vec_stream_close(st);
}

/* Both ways on one file; 1 if the same bytes. */
static int same_both_ways(const unit_desc *u, const char *path, const char *tag)
{
    unit_cfg cfg;
    unit_cfg_default(u, &cfg);
    unit_fmts fm;
    char err[600], csvp[] = "/tmp/shadesim_test_stream_XXXXXX";
    if (tb_formats(u, &cfg, NULL, 0, &fm, err, sizeof err)) { TST_CHECK(0, "%s: %s", tag, err); return 0; }
    vec_set hdr, vs;
    vec_set_init(&hdr);
    tb_expected_header(u, &cfg, &hdr);
    if (vec_file_read(path, &vs, &hdr, err, sizeof err)) { TST_CHECK(0, "%s: %s", tag, err); return 0; }
    tb_result r1, r2;
    membuf j1 = { 0 }, j2 = { 0 }, c2 = { 0 };
    int t1 = tb_run(u, &cfg, &fm, &vs, NULL, &r1, err, sizeof err);
    TST_CHECK(t1 == TB_OK, "%s: %s", tag, err);
    j1.f = open_memstream(&j1.p, &j1.n);
    if (t1 == TB_OK) tb_write_json(j1.f, &r1);
    fclose(j1.f);
    int fd = mkstemp(csvp);
    if (fd >= 0) close(fd);
    if (t1 == TB_OK) TST_CHECK(tb_write_csv(csvp, &r1, &vs, err, sizeof err) == 0, "%s", err);
    size_t n1 = 0;
    char *c1 = slurp(csvp, &n1);
    unlink(csvp);

    vec_stream *st = vec_stream_open(path, &hdr, err, sizeof err);
    TST_CHECK(st != NULL, "%s", err);
    c2.f = open_memstream(&c2.p, &c2.n);
    tb_csv_header(c2.f, vs.n_out, (const char (*)[16])vs.out_names);
    int t2 = st ? tb_run_stream(u, &cfg, &fm, st, row_cb, &c2, NULL, &r2, err, sizeof err) : TB_FAIL;
    TST_CHECK(t2 == TB_OK, "%s: %s", tag, err);
    fclose(c2.f);
    j2.f = open_memstream(&j2.p, &j2.n);
    if (t2 == TB_OK) tb_write_json(j2.f, &r2);
    fclose(j2.f);
    vec_stream_close(st);
    int same = t1 == TB_OK && t2 == TB_OK && j1.n == j2.n && !memcmp(j1.p, j2.p, j1.n)
               && c1 && n1 == c2.n && !memcmp(c1, c2.p, n1);
    TST_CHECK(same, "%s: JSON %zu/%zu bytes, CSV %zu/%zu bytes differ", tag, j1.n, j2.n, n1, c2.n);
    TST_CHECK(t2 != TB_OK || (r2.raw == NULL && r2.beat_cycle == NULL), "%s: nothing per item kept", tag);
    if (t1 == TB_OK) same_on_lanes(u, &cfg, &fm, path, &hdr, &j1, c1, n1, tag);
    if (t1 == TB_OK) tb_result_free(&r1);
    if (t2 == TB_OK) tb_result_free(&r2);
    free(j1.p); free(j2.p); free(c2.p); free(c1);
    vec_set_free(&vs);
    return same;
}

static void t_every_unit(void)
{
    int done = 0;
    for (size_t i = 0, n = unit_count(); i < n; i++) {
        const unit_desc *u = unit_at(i);
        char path[256];
        snprintf(path, sizeof path, "vectors/%s.vec", u->name);
        if (access(path, R_OK)) continue;   /* a unit without checked-in vectors */
        same_both_ways(u, path, u->name);
        done++;
    }
    TST_CHECK(done >= 15, "only %d units have vectors", done);
}

static void t_many_blocks(void)
{
    /* 45,000 items: over 4 MB of text (two blocks of the reader) and more
     * items than the ring's slots (so slots are reused). */
    const unit_desc *u = unit_find("horner3");
    unit_cfg cfg;
    unit_cfg_default(u, &cfg);
    vec_set vs;
    char err[600], path[] = "/tmp/shadesim_test_stream_XXXXXX";
    int fd = mkstemp(path);
    if (fd >= 0) close(fd);
    TST_CHECK(tb_make_vectors(u, &cfg, 45000, 3, &vs, err, sizeof err) == 0, "%s", err);
    TST_CHECK(vec_file_write(path, &vs, err, sizeof err) == 0, "%s", err);
    vec_set_free(&vs);
    same_both_ways(u, path, "horner3 45000");

    /* A bad row far into the file: the same message as a whole read. */
    FILE *f = fopen(path, "a");
    if (f) { fputs("0.1 0.2 0.3 0.4 nope | 0.5\n", f); fclose(f); }
    vec_set hdr;
    vec_set_init(&hdr);
    tb_expected_header(u, &cfg, &hdr);
    char want[600] = "", got[600] = "";
    TST_CHECK(vec_file_read(path, &vs, &hdr, want, sizeof want) != 0, "the bad row is refused");
    vec_stream *st = vec_stream_open(path, &hdr, err, sizeof err);
    unit_fmts fm;
    tb_formats(u, &cfg, NULL, 0, &fm, err, sizeof err);
    tb_result r;
    int t = st ? tb_run_stream(u, &cfg, &fm, st, NULL, NULL, NULL, &r, got, sizeof got) : TB_FAIL;
    vec_stream_close(st);
    TST_EQ_INT(t, TB_BADINPUT);
    TST_EQ_STR(got, want);
    TST_CHECK(strstr(want, ":45005: not a number: 'nope'") != NULL, "%s", want);
    unlink(path);
}

int main(void)
{
    TST_RUN(t_every_unit);
    TST_RUN(t_many_blocks);
    TST_EXIT();
}
