/* tb_sweep.c - the sweep engine: configurations, threads, shards, the CSV,
 * merging shards, and the per-signal format search. */
#include "testbench/study/tb_sweep.h"
#include "testbench/tb_stream.h"
#include "vectors/vec_file.h"
#include "base/base_line.h"
#include "base/base_out.h"
#include "base/base_par.h"
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* ------------------------------------------------------------- utilities */

/* tb_afile is base_out under the sweep's names: a regular file (or a new
 * path, or a symlink's target) replaced atomically once complete, with a
 * registered temporary that SIGINT/SIGTERM/SIGHUP remove; a device or
 * FIFO written through; "-" is stdout. */
int tb_afile_open(tb_afile *a, const char *path, char *err, size_t errlen)
{
    a->path = path;
    a->out = base_out_open(path, err, errlen);
    a->f = a->out ? base_out_file(a->out) : NULL;
    return a->out ? 0 : -1;
}

int tb_afile_commit(tb_afile *a, char *err, size_t errlen)
{
    int rc = base_out_close(a->out, err, errlen);
    a->out = NULL;
    a->f = NULL;
    return rc;
}

void tb_afile_abort(tb_afile *a)
{
    base_out_abort(a->out);
    a->out = NULL;
    a->f = NULL;
}

/* ------------------------------------------------------- configurations */

int tb_sweep_in_shard(size_t i, int k, int n)
{
    return n <= 0 || i % (size_t)n == (size_t)(k - 1);
}

int tb_sweep_init(tb_sweep *s, const tb_sweep_spec *sp, char *err, size_t errlen)
{
    memset(s, 0, sizeof *s);
    s->spec = *sp;
    const unit_desc *u = sp->u;
    size_t ng = (size_t)sp->nsched * (size_t)sp->nrnd * (size_t)sp->novf, np = 1;
    for (int a = 0; a < sp->npax; a++) np *= (size_t)sp->pax[a].n;
    ng *= np;
    size_t nw = (size_t)(sp->whi - sp->wlo + 1);
    if (ng == 0 || sp->whi < sp->wlo) { snprintf(err, errlen, "sweep: nothing to run"); return -1; }
    if (ng > TB_SWEEP_MAX_CONFIGS / nw) {
        snprintf(err, errlen, "sweep: %zu widths x %zu settings is more than %d configurations",
                 nw, ng, TB_SWEEP_MAX_CONFIGS);
        return -1;
    }
    s->ngroups = ng;
    s->npsets = np;
    s->n = nw * ng;
    s->cfg = calloc(s->n, sizeof *s->cfg);
    s->row = calloc(s->n, sizeof *s->row);
    s->vs = calloc(np, sizeof *s->vs);
    if (!s->cfg || !s->row || !s->vs) base_out_of_memory();
    for (size_t i = 0; i < s->n; i++) {
        tb_sweep_cfg *c = &s->cfg[i];
        size_t g = i % ng, pset = 0, mul = 1;
        c->group = g;
        c->cfg = sp->base;
        c->cfg.width = sp->wlo + (int)(i / ng);
        /* Mixed radix, the last axis fastest: overflow, round, params
         * (last given fastest), schedule. */
        c->cfg.ovf = sp->ovf[g % (size_t)sp->novf]; g /= (size_t)sp->novf;
        c->cfg.rnd = sp->rnd[g % (size_t)sp->nrnd]; g /= (size_t)sp->nrnd;
        for (int a = sp->npax - 1; a >= 0; a--) {
            const tb_sweep_paxis *ax = &sp->pax[a];
            size_t v = g % (size_t)ax->n;
            g /= (size_t)ax->n;
            pset += v * mul;
            mul *= (size_t)ax->n;
            if (unit_param_set(u, &c->cfg, u->params[ax->param].name, ax->val[v], err, errlen)) {
                tb_sweep_free(s);
                return -1;
            }
        }
        c->cfg.schedule = sp->sched[g];
        c->pset = pset;
        if (tb_formats(u, &c->cfg, sp->fmt, sp->nfmt, &c->fmts, err, errlen)) { tb_sweep_free(s); return -1; }
        s->row[i].status = TB_SWEEP_NOT_RUN;
    }
    return 0;
}

int tb_sweep_min_width(const tb_sweep_spec *spec, int *limit_sig, unit_cfg *limit_cfg)
{
    tb_sweep_spec sp = *spec;
    tb_sweep s;
    char err[400];
    int wmin = 1;
    *limit_sig = -1;
    *limit_cfg = spec->base;
    for (int k = 0; k < sp.nfmt; k++)
        if (!strncmp(sp.fmt[k], "all=", 4)) return 1;
    /* Every group's configuration at one width that any rule can build. */
    sp.wlo = sp.whi = 64;
    if (tb_sweep_init(&s, &sp, err, sizeof err)) return 1;   /* tb_sweep_init proper will say why */
    for (size_t i = 0; i < s.n; i++) {
        int lim, w = unit_min_width(sp.u, &s.cfg[i].cfg, &lim);
        if (w > wmin) { wmin = w; *limit_sig = lim; *limit_cfg = s.cfg[i].cfg; }
    }
    tb_sweep_free(&s);
    return wmin;
}

void tb_sweep_free(tb_sweep *s)
{
    free(s->cfg);
    free(s->row);
    free(s->vs);
    s->cfg = NULL;
    s->row = NULL;
    s->vs = NULL;
}

const unit_cfg *tb_sweep_pset_cfg(const tb_sweep *s, size_t p)
{
    /* The parameter sets all occur within the first width's groups. */
    for (size_t i = 0; i < s->ngroups; i++)
        if (s->cfg[i].pset == p) return &s->cfg[i].cfg;
    return NULL;
}

void tb_sweep_group_label(const tb_sweep *s, size_t group, char *buf, size_t len)
{
    const tb_sweep_spec *sp = &s->spec;
    const unit_cfg *c = &s->cfg[group].cfg;
    size_t k = 0;
    buf[0] = 0;
#define ADD(...) do { if (k < len) k += (size_t)snprintf(buf + k, len - k, __VA_ARGS__); } while (0)
    if (sp->nsched > 1) ADD("%s%s", k ? " " : "", sp->u->sched[c->schedule].name);
    for (int a = 0; a < sp->npax; a++) {
        if (sp->pax[a].n < 2) continue;
        char v[64];
        const unit_param *p = &sp->u->params[sp->pax[a].param];
        unit_param_get(p, c, v, sizeof v);
        ADD("%s%s=%s", k ? " " : "", p->name, v);
    }
    if (sp->nrnd > 1) ADD("%s%s", k ? " " : "", sim_round_name(c->rnd));
    if (sp->novf > 1) ADD("%s%s", k ? " " : "", sim_ovf_name(c->ovf));
#undef ADD
}

/* ---------------------------------------------------------------- running */

typedef struct run_job {
    tb_sweep *s;
    size_t *idx, total, done, failed;
    pthread_mutex_t mu;
    tb_sweep_progress_fn progress;
    void *arg;
} run_job;

void tb_sweep_stream(tb_sweep *s, size_t n, uint64_t seed)
{
    s->stream = 1;
    s->gen_n = n;
    s->gen_seed = seed;
}

void tb_sweep_stream_file(tb_sweep *s, const char *path)
{
    s->stream = 1;
    s->path = path;
}

/* Parameter set p's rows as a stream: the file's (its header checked
 * against the unit's for the set's configuration) or the generator's. */
static vec_stream *open_rows(const tb_sweep *s, const unit_cfg *cfg, char *err, size_t errlen)
{
    const unit_desc *u = s->spec.u;
    vec_set hdr;
    vec_set_init(&hdr);
    tb_expected_header(u, cfg, &hdr);
    if (s->path) return vec_stream_open(s->path, &hdr, err, errlen);
    return vec_stream_gen(u->ref, &cfg->model, s->gen_n, s->gen_seed, &hdr, err, errlen);
}

size_t tb_sweep_rows(const tb_sweep *s, size_t p)
{
    return s->stream ? s->gen_n : s->vs[p]->n_rows;
}

/* Configuration c on its parameter set's rows as streamed (tb_run_stream:
 * the kernel, a block of rows at a time). */
static int run_streamed(const tb_sweep *s, const tb_sweep_cfg *c, tb_sweep_row *row)
{
    const unit_desc *u = s->spec.u;
    vec_stream *vs = open_rows(s, &c->cfg, row->err, sizeof row->err);
    if (!vs) return TB_BADINPUT;
    int rc = tb_run_stream(u, &c->cfg, &c->fmts, vs, NULL, NULL, NULL, &row->r, row->err, sizeof row->err);
    vec_stream_close(vs);
    return rc;
}

static void run_one(void *ctx, size_t k)
{
    run_job *j = ctx;
    size_t i = j->idx[k];
    const tb_sweep_cfg *c = &j->s->cfg[i];
    tb_sweep_row *row = &j->s->row[i];
    if (j->s->stream) row->status = run_streamed(j->s, c, row);
    else row->status = tb_run(j->s->spec.u, &c->cfg, &c->fmts, j->s->vs[c->pset], NULL, &row->r,
                              row->err, sizeof row->err);
    if (row->status == TB_OK) tb_verdict(&row->r, &j->s->spec.accept);   /* the user's targets */
    tb_result_free(&row->r);
    pthread_mutex_lock(&j->mu);
    j->done++;
    if (row->status != TB_OK) j->failed++;
    if (j->progress) j->progress(j->arg, j->done, j->total);
    pthread_mutex_unlock(&j->mu);
}

size_t tb_sweep_run(tb_sweep *s, int threads, int shard_k, int shard_n,
                    tb_sweep_progress_fn progress, void *arg)
{
    run_job j = { s, NULL, 0, 0, 0, PTHREAD_MUTEX_INITIALIZER, progress, arg };
    j.idx = malloc(s->n * sizeof *j.idx);
    if (!j.idx) base_out_of_memory();
    for (size_t i = 0; i < s->n; i++)
        if (tb_sweep_in_shard(i, shard_k, shard_n)) j.idx[j.total++] = i;
    base_par_for(j.total, threads, run_one, &j);
    free(j.idx);
    pthread_mutex_destroy(&j.mu);
    return j.failed;
}

/* ----------------------------------------------------------- fingerprint */

static uint64_t fnv(uint64_t h, const void *p, size_t n)
{
    const unsigned char *b = p;
    for (size_t i = 0; i < n; i++) { h ^= b[i]; h *= 1099511628211ull; }
    return h;
}
static uint64_t fnv_s(uint64_t h, const char *s) { return fnv(h, s, strlen(s) + 1); }

/* The identity columns of configuration i: unit..overflow. */
static void ident(FILE *f, const tb_sweep *s, size_t i)
{
    const unit_desc *u = s->spec.u;
    const unit_cfg *c = &s->cfg[i].cfg;
    fprintf(f, "%s,%s,%d", u->name, u->sched[c->schedule].name, c->width);
    for (int p = 0; p < u->nparams; p++) {
        char v[64];
        unit_param_get(&u->params[p], c, v, sizeof v);
        fprintf(f, ",%s", v);
    }
    fprintf(f, ",%s,%s", sim_round_name(c->rnd), sim_ovf_name(c->ovf));
}

/* Streamed: the rows as fnv hashes a held set's, generated once more.
 * 0, or -1 with a message. */
static int hash_stream(tb_sweep *s, size_t p, uint64_t *h, char *err, size_t errlen)
{
    const unit_cfg *cfg = tb_sweep_pset_cfg(s, p);
    size_t n = 0;
    const vec_set *rows;
    int rc;
    vec_stream *vs;
    if (s->path) {
        /* the count comes first in the hash: a pass to count the rows (and
         * find what is wrong with the file, as a whole read would) */
        if (!(vs = open_rows(s, cfg, err, errlen))) return -1;
        while ((rc = vec_stream_next(vs, &rows)) > 0) n += rows->n_rows;
        if (rc < 0) snprintf(err, errlen, "%s", vec_stream_error(vs));
        vec_stream_close(vs);
        if (rc < 0) return -1;
        s->gen_n = n;
        n = 0;
    }
    if (!(vs = open_rows(s, cfg, err, errlen))) return -1;
    *h = fnv(*h, &s->gen_n, sizeof s->gen_n);
    while ((rc = vec_stream_next(vs, &rows)) > 0) {
        *h = fnv(*h, rows->data, rows->n_rows * (size_t)(rows->n_in + rows->n_out) * sizeof *rows->data);
        n += rows->n_rows;
    }
    if (rc < 0 || n != s->gen_n) {
        if (rc < 0 && s->path) snprintf(err, errlen, "%s", vec_stream_error(vs));
        else snprintf(err, errlen, "%s: %s", s->spec.u->name, rc < 0 ? vec_stream_error(vs) : "the vectors changed while read");
        rc = -1;
    }
    vec_stream_close(vs);
    return rc;
}

int tb_sweep_fingerprint(tb_sweep *s, char *err, size_t errlen)
{
    uint64_t h = 14695981039346656037ull;
    char buf[2048], fb[SIM_FMT_STRLEN];
    for (size_t i = 0; i < s->n; i++) {
        FILE *m = fmemopen(buf, sizeof buf, "w");
        if (m) { ident(m, s, i); fputc(0, m); fclose(m); }
        buf[sizeof buf - 1] = 0;
        h = fnv_s(h, buf);
        for (int k = 0; k < s->spec.u->nsigs; k++) h = fnv_s(h, sim_fmt_str(s->cfg[i].fmts.f[k], fb));
    }
    for (size_t p = 0; p < s->npsets; p++) {
        const vec_set *v = s->vs[p];
        if (!v) continue;
        h = fnv_s(h, v->unit);
        for (int k = 0; k < v->n_in; k++) h = fnv_s(h, v->in_names[k]);
        for (int k = 0; k < v->n_out; k++) h = fnv_s(h, v->out_names[k]);
        if (s->stream) {
            if (hash_stream(s, p, &h, err, errlen)) return -1;
            continue;
        }
        h = fnv(h, &v->n_rows, sizeof v->n_rows);
        h = fnv(h, v->data, v->n_rows * (size_t)(v->n_in + v->n_out) * sizeof *v->data);
    }
    /* Shards judged against other acceptance would disagree on
     * meets_target: another sweep. (Without acceptance the id is as it was.) */
    const tb_accept *ac = &s->spec.accept;
    if (ac->max_error > 0 || ac->max_nmse > 0 || ac->max_lsb > 0) {
        h = fnv(h, &ac->max_error, sizeof ac->max_error);
        h = fnv(h, &ac->max_nmse, sizeof ac->max_nmse);
        h = fnv(h, &ac->max_lsb, sizeof ac->max_lsb);
    }
    s->id = h;
    return 0;
}

/* -------------------------------------------------------------------- CSV */

/* Numbers as run --json prints them (%.17g reads back exactly), but a CSV
 * can say inf and nan, which pandas and R read. */
static void cnum(FILE *f, double v)
{
    if (isnan(v)) fputs(",nan", f);
    else if (isinf(v)) fputs(v > 0 ? ",inf" : ",-inf", f);
    else fprintf(f, ",%.17g", v);
}

static const char *const out_fields[] = { "max_abs_err", "mean_err", "rms_err", "nmse", "max_err_lsb",
                                          "bound", "max_err_vs_ideal" };
#define N_OUT_FIELDS 7
#define N_FIGURES 22   /* vectors .. meets_target */

static void csv_header(FILE *f, const unit_desc *u)
{
    fputs("config,n_configs,sweep_id,unit,schedule,width", f);
    for (int p = 0; p < u->nparams; p++) fprintf(f, ",%s", u->params[p].name);
    fputs(",round,overflow,status,vectors,beats_per_item,cycles,cycles_per_item,cycles_per_beat,latency,"
          "max_abs_err,mean_err,rms_err,nmse,max_err_lsb,overflows,area_ge,crit_levels,crit_ps,fmax_mhz,items_per_s,"
          "pixels_per_s,energy_pj_per_item,energy_pj_per_pixel,within_bound,meets_target", f);
    for (int i = 0; i < u->nsigs; i++)
        if (u->sigs[i].role == UNIT_SIG_OUT)
            for (int k = 0; k < N_OUT_FIELDS; k++) fprintf(f, ",%s_%s", u->sigs[i].name, out_fields[k]);
    for (int i = 0; i < u->nsigs; i++) fprintf(f, ",fmt_%s", u->sigs[i].name);
    fputs(",sim_clocks,sim_events,sim_delta_cycles,sim_process_runs\n", f);
}

static void csv_row(FILE *f, const tb_sweep *s, size_t i)
{
    const unit_desc *u = s->spec.u;
    const tb_sweep_row *row = &s->row[i];
    const tb_result *r = &row->r;
    int ok = row->status == TB_OK, nout = unit_n_out(u);
    char fb[SIM_FMT_STRLEN];
    fprintf(f, "%zu,%zu,%016llx,", i, s->n, (unsigned long long)s->id);
    ident(f, s, i);
    fputs(ok ? ",ok" : row->status == TB_BADINPUT ? ",not_buildable" : ",failed", f);
    if (ok) {
        fprintf(f, ",%zu,%d,%llu", r->vectors, r->beats, (unsigned long long)r->cycles);
        cnum(f, r->cycles_per_item);
        cnum(f, r->cycles_per_beat);
        fprintf(f, ",%llu", (unsigned long long)r->latency);
        cnum(f, r->max_abs_err); cnum(f, r->mean_err); cnum(f, r->rms_err);
        cnum(f, r->nmse); cnum(f, r->max_err_lsb);
        fprintf(f, ",%llu", (unsigned long long)r->overflows);
        cnum(f, r->area_ge);
        /* Speed and energy (docs/timing.md): a pixel is an output beat. */
        fprintf(f, ",%d", r->ppa.levels);
        cnum(f, r->ppa.crit_ps); cnum(f, r->ppa.fmax_mhz); cnum(f, r->ppa.items_per_s);
        cnum(f, tb_pixels_per_s(r)); cnum(f, r->ppa.energy_pj_per_item); cnum(f, tb_energy_pj_per_pixel(r));
        fputs(r->within_bound ? ",true" : ",false", f);
        /* Empty without --max-error/--max-nmse/--max-lsb: no target to meet. */
        fputs(!r->target_set ? "," : r->target_met ? ",true" : ",false", f);
        for (int o = 0; o < nout; o++) {
            const tb_metrics *m = &r->out[o];
            cnum(f, m->max_abs_err); cnum(f, m->mean_err); cnum(f, m->rms_err); cnum(f, m->nmse);
            cnum(f, m->max_err_lsb); cnum(f, m->bound); cnum(f, m->max_err_ideal);
        }
    } else {
        /* A failed simulation has no figures: empty cells, not zeros. */
        for (int k = 0; k < N_FIGURES + nout * N_OUT_FIELDS; k++) fputc(',', f);
    }
    for (int k = 0; k < u->nsigs; k++) fprintf(f, ",%s", sim_fmt_str(s->cfg[i].fmts.f[k], fb));
    if (ok) fprintf(f, ",%llu,%llu,%llu,%llu\n", (unsigned long long)r->stats.clocks,
                    (unsigned long long)r->stats.events, (unsigned long long)r->stats.deltas,
                    (unsigned long long)r->stats.proc_runs);
    else fputs(",,,,\n", f);
}

void tb_sweep_print_csv(const tb_sweep *s, FILE *f, int shard_k, int shard_n)
{
    csv_header(f, s->spec.u);
    for (size_t i = 0; i < s->n; i++)
        if (tb_sweep_in_shard(i, shard_k, shard_n)) csv_row(f, s, i);
}

int tb_sweep_write_csv(const tb_sweep *s, const char *path, int shard_k, int shard_n,
                       char *err, size_t errlen)
{
    tb_afile a;
    if (tb_afile_open(&a, path, err, errlen)) return -1;
    tb_sweep_print_csv(s, a.f, shard_k, shard_n);
    return tb_afile_commit(&a, err, errlen);
}

/* ------------------------------------------------------------------ merge */

typedef struct mrow {
    size_t idx;
    int file, line;
    const char *text;   /* the line, without its newline */
} mrow;

static int mrow_cmp(const void *a, const void *b)
{
    const mrow *x = a, *y = b;
    if (x->idx != y->idx) return x->idx < y->idx ? -1 : 1;
    if (x->file != y->file) return x->file - y->file;
    return x->line - y->line;
}

static size_t count_commas(const char *s)
{
    size_t n = 0;
    for (; *s; s++) n += *s == ',';
    return n;
}

/* Field k (0-based) of a line into buf. */
static void field(const char *line, int k, char *buf, size_t len)
{
    while (k-- > 0 && (line = strchr(line, ','))) line++;
    if (!line) { buf[0] = 0; return; }
    size_t n = strcspn(line, ",");
    snprintf(buf, len, "%.*s", (int)(n < len ? n : len - 1), line);
}

static int parse_index(const char *s, size_t *v)
{
    if (!*s || strspn(s, "0123456789") != strlen(s) || strlen(s) > 15) return -1;
    *v = (size_t)strtoull(s, NULL, 10);
    return 0;
}

int tb_sweep_merge(const char *const *paths, int n, const char *out, char *err, size_t errlen)
{
    char **text = calloc((size_t)n, sizeof *text);
    mrow *rows = NULL;
    size_t nrows = 0, cap = 0, total = 0;
    const char *header = NULL;
    char id[64] = "";
    int rc = -1;
    if (!text) base_out_of_memory();
    for (int fi = 0; fi < n; fi++) {
        size_t len;
        const char *p = paths[fi];
        if (!(text[fi] = base_text_read(p, TB_SWEEP_MAX_LINE, &len, err, errlen))) goto done;
        char *line = text[fi];
        for (int ln = 1; *line; ln++) {
            char *nl = strchr(line, '\n');
            if (nl) *nl = 0;
            char *next = nl ? nl + 1 : line + strlen(line);
            if (ln == 1) {
                if (strncmp(line, "config,n_configs,sweep_id,", 26)) {
                    snprintf(err, errlen, "%s:1: not a shadesim sweep CSV (header should start config,n_configs,sweep_id)", p);
                    goto done;
                }
                if (!header) header = line;
                else if (strcmp(header, line)) {
                    snprintf(err, errlen, "%s:1: header differs from %s's (another unit or version?)", p, paths[0]);
                    goto done;
                }
                line = next;
                continue;
            }
            if (count_commas(line) != count_commas(header)) {
                snprintf(err, errlen, "%s:%d: %zu fields, the header has %zu", p, ln, count_commas(line) + 1,
                         count_commas(header) + 1);
                goto done;
            }
            char f0[32], f1[32], f2[64];
            size_t idx, tot;
            field(line, 0, f0, sizeof f0);
            field(line, 1, f1, sizeof f1);
            field(line, 2, f2, sizeof f2);
            if (parse_index(f0, &idx) || parse_index(f1, &tot) || idx >= tot) {
                snprintf(err, errlen, "%s:%d: bad configuration index '%s' of '%s'", p, ln, f0, f1);
                goto done;
            }
            if (!nrows && !total) { total = tot; snprintf(id, sizeof id, "%s", f2); }
            if (tot != total || strcmp(id, f2)) {
                snprintf(err, errlen, "%s:%d: row of another sweep (%s of %s configurations; expected %s of %zu)",
                         p, ln, f2, f1, id, total);
                goto done;
            }
            if (nrows == cap) {
                cap = cap ? cap * 2 : 256;
                mrow *nr = realloc(rows, cap * sizeof *rows);
                if (!nr) base_out_of_memory();
                rows = nr;
            }
            rows[nrows++] = (mrow){ idx, fi, ln, line };
            line = next;
        }
        if (!header || text[fi][0] == 0) { snprintf(err, errlen, "%s: empty file", p); goto done; }
    }
    if (!nrows) { snprintf(err, errlen, "merge: the files hold no rows"); goto done; }
    qsort(rows, nrows, sizeof *rows, mrow_cmp);
    for (size_t k = 1; k < nrows; k++)
        if (rows[k].idx == rows[k - 1].idx) {
            snprintf(err, errlen, "configuration %zu twice: %s:%d and %s:%d", rows[k].idx,
                     paths[rows[k - 1].file], rows[k - 1].line, paths[rows[k].file], rows[k].line);
            goto done;
        }
    if (nrows != total) {
        size_t miss = 0, k = 0;
        while (k < nrows && rows[k].idx == miss) { k++; miss++; }
        snprintf(err, errlen, "%zu of %zu configurations missing (the first is configuration %zu): a shard not given?",
                 total - nrows, total, miss);
        goto done;
    }
    tb_afile a;
    if (tb_afile_open(&a, out, err, errlen)) goto done;
    fprintf(a.f, "%s\n", header);
    for (size_t k = 0; k < nrows; k++) fprintf(a.f, "%s\n", rows[k].text);
    rc = tb_afile_commit(&a, err, errlen);
done:
    for (int fi = 0; fi < n; fi++) free(text[fi]);
    free(text);
    free(rows);
    return rc;
}

/* ---------------------------------------------------------- target search */

int tb_sweep_holds(const tb_sweep *s, const tb_result *r, int status, tb_target_kind k, double target,
                   uint64_t max_ovf)
{
    return tb_target_holds(r, status, k, target, max_ovf) && tb_ppa_meets(r, &s->spec.ppa, NULL, 0);
}

typedef struct cand_job {
    const tb_sweep *s;
    const tb_sweep_cfg *c;
    unit_fmts f;
    tb_result r;
    int status;
    char err[240];
    const unsigned char *keep;   /* --ranges derived: the pinned signals; NULL: observed */
} cand_job;

static void cand_run(void *ctx, size_t i)
{
    cand_job *j = (cand_job *)ctx + i;
    if (!j->c) return;     /* nothing to remove */
    /* --ranges derived: the candidate's integer bits follow its fraction bits */
    if (j->keep && tb_sweep_derive(j->s, j->c, j->keep, &j->f, j->err, sizeof j->err)) { j->status = TB_FAIL; return; }
    j->status = tb_run(j->s->spec.u, &j->c->cfg, &j->f, j->s->vs[j->c->pset], NULL, &j->r, j->err, sizeof j->err);
    tb_result_free(&j->r);
}

typedef struct cand_t {
    int sig, kind;          /* kind 0: a fraction bit, 1: an integer bit */
    double saving;          /* GE saved from the start design; -1: none */
    int order;
} cand_t;

static int cand_cmp(const void *a, const void *b)
{
    const cand_t *x = a, *y = b;
    if (x->saving != y->saving) return x->saving > y->saving ? -1 : 1;
    return x->order - y->order;
}

/* Signal sig's format one bit shorter: kind 0 a fraction bit, 1 an integer
 * bit. 0, or -1 if it has none to give (a signed format keeps its sign
 * bit, and every format at least one bit). */
static int shorter(sim_fmt f, int kind, sim_fmt *out)
{
    if (f.width < 2) return -1;
    if (kind == 0) {
        if (f.fbits < 1) return -1;
        f.fbits--;
    } else {
        if (f.ibits <= (f.is_signed ? 1 : 0)) return -1;
        f.ibits--;
    }
    f.width--;
    *out = f;
    return 0;
}

/* A signal the user fixed with --fmt NAME=... (or all=...) keeps its
 * format: an interface format is a given, not a choice. */
static int pinned(const tb_sweep *s, int sig)
{
    const char *name = s->spec.u->sigs[sig].name;
    for (int k = 0; k < s->spec.nfmt; k++) {
        const char *o = s->spec.fmt[k];
        size_t n = strcspn(o, "=");
        if ((n == 3 && !strncmp(o, "all", 3)) || (n == strlen(name) && !strncmp(o, name, n))) return 1;
    }
    return 0;
}

int tb_sweep_target(const tb_sweep *s, size_t group, tb_target_kind k, double target,
                    int threads, tb_target_res *out, char *err, size_t errlen)
{
    const unit_desc *u = s->spec.u;
    memset(out, 0, sizeof *out);
    out->group = group;
    /* The start: the smallest uniform width that meets the error rule.
     * The speed and energy limits are not asked of it: bits the search
     * removes shorten paths and save toggles, so a design that meets them
     * may lie below a start that does not. */
    for (size_t i = group; i < s->n; i += s->ngroups)
        if (tb_target_holds(&s->row[i].r, s->row[i].status, k, target, UINT64_MAX)) {
            out->met = 1;
            out->uniform = i;
            break;
        }
    if (!out->met && !s->spec.ranges) return 0;
    /* Under derived ranges the start has derived integer bits, only
     * fraction bits are searched, and no overflow is accepted. */
    unsigned char keep[UNIT_MAX_SIGS] = { 0 };
    const unsigned char *dkeep = NULL;
    if (s->spec.ranges) {
        for (int i = 0; i < u->nsigs; i++) keep[i] = (unsigned char)pinned(s, i);
        dkeep = keep;
        if (tb_sweep_derived_start(s, group, k, target, keep, out, err, errlen)) return -1;
        if (!out->met) return 0;
    }
    const tb_sweep_cfg *c = &s->cfg[out->uniform];
    uint64_t max_ovf = s->row[out->uniform].r.overflows;   /* derived ranges: none (tb_target_holds_derived) */
    if (!dkeep) {
        out->fmts = c->fmts;
        out->r = s->row[out->uniform].r;
    }
    if (threads < 1) threads = 1;
    if (threads > 64) threads = 64;
    int nc = 2 * u->nsigs;
    /* nc jobs for the first round, `threads` for each batch after it. */
    cand_job *jobs = calloc((size_t)(nc > threads ? nc : threads), sizeof *jobs);
    cand_t *cand = malloc((size_t)nc * sizeof *cand);
    if (!jobs || !cand) base_out_of_memory();
    /* Every single-bit removal from the start, all at once: the area each
     * saves orders the passes, dearest bits first, so that the error
     * budget goes where it buys the most area (ties: fraction before
     * integer bit, signals as the unit lists them). */
    for (int q = 0; q < nc; q++) {
        cand[q] = (cand_t){ q / 2, q % 2, -1.0, q };
        jobs[q].s = s;
        jobs[q].c = c;
        jobs[q].f = out->fmts;
        jobs[q].status = TB_SWEEP_NOT_RUN;
        jobs[q].keep = dkeep;
        /* Pinned signals stay; signals the schedule does not build have
         * nothing to trim; derived integer bits are not searched. */
        if (pinned(s, q / 2) || !unit_sig_built(u, q / 2, &c->cfg) || (dkeep && q % 2)) cand[q].sig = -1;
        if (cand[q].sig < 0 || shorter(out->fmts.f[q / 2], q % 2, &jobs[q].f.f[q / 2])) jobs[q].c = NULL;
    }
    base_par_for((size_t)nc, threads, cand_run, jobs);
    for (int q = 0; q < nc; q++) {
        if (jobs[q].status == TB_SWEEP_NOT_RUN) continue;
        out->runs++;
        if (jobs[q].status == TB_OK) cand[q].saving = out->r.area_ge - jobs[q].r.area_ge;
    }
    qsort(cand, (size_t)nc, sizeof *cand, cand_cmp);
    for (int changed = 1; changed;) {
        changed = 0;
        for (int next = 0; next < nc;) {
            /* Up to `threads` applicable candidates from the current
             * formats, run together; the first that holds is taken and
             * the pass goes on after it, so the outcome is the same as
             * trying them one by one. */
            int nb = 0, pos[64];
            while (next < nc && nb < threads) {
                sim_fmt f;
                if (cand[next].sig >= 0 && !shorter(out->fmts.f[cand[next].sig], cand[next].kind, &f)) {
                    jobs[nb].s = s;
                    jobs[nb].c = c;
                    jobs[nb].f = out->fmts;
                    jobs[nb].f.f[cand[next].sig] = f;
                    jobs[nb].keep = dkeep;
                    pos[nb++] = next;
                }
                next++;
            }
            if (!nb) break;
            base_par_for((size_t)nb, threads, cand_run, jobs);
            for (int b = 0; b < nb; b++) {
                out->runs++;
                /* While the design misses the limits, any removal that
                 * keeps the error rule is taken; once it meets them, only
                 * one that keeps them met too. */
                int lim = tb_ppa_meets(&out->r, &s->spec.ppa, NULL, 0);
                if ((dkeep ? tb_target_holds_derived(&jobs[b].r, jobs[b].status, k, target)
                           : tb_target_holds(&jobs[b].r, jobs[b].status, k, target, max_ovf))
                    && (!lim || tb_ppa_meets(&jobs[b].r, &s->spec.ppa, NULL, 0))) {
                    out->fmts = jobs[b].f;
                    out->r = jobs[b].r;
                    next = pos[b] + 1;
                    changed = 1;
                    break;
                }
            }
        }
    }
    free(jobs);
    free(cand);
    /* The limits are met by the result, or nothing is: met says so. */
    if (!tb_ppa_meets(&out->r, &s->spec.ppa, out->limits_why, sizeof out->limits_why)) out->met = 0;
    return 0;
}

double tb_target_goal(tb_target_kind k, double target, double bits)
{
    return ldexp(target, -(int)lround((k == TB_TARGET_NMSE ? 2 : 1) * bits));
}

int tb_sweep_target_heldout(const tb_sweep *s, const vec_set *ho, tb_target_kind k, double target,
                            tb_target_res *out, char *err, size_t errlen)
{
    if (!out->met) return 0;
    const tb_sweep_cfg *c = &s->cfg[out->uniform];
    char e1[240], e2[240];
    int su = tb_run(s->spec.u, &c->cfg, &c->fmts, ho, NULL, &out->heldout_u, e1, sizeof e1);
    tb_result_free(&out->heldout_u);
    out->heldout_status = tb_run(s->spec.u, &c->cfg, &out->fmts, ho, NULL, &out->heldout_r, e2, sizeof e2);
    tb_result_free(&out->heldout_r);
    if (su == TB_BADINPUT || out->heldout_status == TB_BADINPUT) {
        snprintf(err, errlen, "held-out check: %s", su == TB_BADINPUT ? e1 : e2);
        return -1;
    }
    out->heldout = 1;
    const tb_result *r = &out->heldout_r;
    double v = k == TB_TARGET_NMSE ? r->nmse : r->max_abs_err;
    uint64_t uo = su == TB_OK ? out->heldout_u.overflows : 0;
    out->heldout_why[0] = 0;
    if (out->heldout_status != TB_OK)
        snprintf(out->heldout_why, sizeof out->heldout_why, "the simulation failed: %.200s", e2);
    else if (!r->within_bound && r->bound_check != TB_CHECK_NO_BOUND)
        snprintf(out->heldout_why, sizeof out->heldout_why, "an output exceeds its error bound");
    else if (!(v <= target))
        snprintf(out->heldout_why, sizeof out->heldout_why, "%s %.4g > target %g",
                 k == TB_TARGET_NMSE ? "NMSE" : "max |e|", v, target);
    else if (r->overflows > uo)
        snprintf(out->heldout_why, sizeof out->heldout_why, "%llu overflows, the uniform design %llu",
                 (unsigned long long)r->overflows, (unsigned long long)uo);
    else {
        char why[160];
        if (!tb_ppa_meets(r, &s->spec.ppa, why, sizeof why))
            snprintf(out->heldout_why, sizeof out->heldout_why, "%s", why);
    }
    out->heldout_ok = !out->heldout_why[0];
    return 0;
}
