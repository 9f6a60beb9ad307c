/* cli_sweep.c - the verb sweep: the vectors, the run of every
 * configuration and a shard's CSV; the options are cli_sweep_opts.c's, the
 * whole sweep's files cli_sweep_summary.c's, the target search
 * cli_sweep_target.c's. */
#include "testbench/cli/cli_sweep.h"
#include "testbench/cli/cli_opt.h"
#include "base/base_proc.h"
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------------------- progress */

typedef struct progress { const char *unit; double t0, last; int shown; } progress;

static void on_progress(void *arg, size_t done, size_t total)
{
    progress *p = arg;
    double t = base_proc_now();
    if (done < total && t - p->last < 0.1) return;
    p->last = t;
    p->shown = 1;
    fprintf(stderr, "\rshadesim sweep %s: %zu/%zu configurations, %.1f s ", p->unit, done, total, t - p->t0);
    fflush(stderr);
}

static void progress_clear(progress *p)
{
    if (p->shown) fputs("\r\033[K", stderr);
    p->shown = 0;
}

/* Vectors per parameter set: each set's own (a parameter like L changes
 * the outputs), loaded once and shared read-only by the threads. Made
 * ones (-n) and a file (--vectors) are streamed instead, each
 * configuration generating or reading its own a block at a time (memory
 * flat in n), unless a target search or --ranges derived runs them again
 * and again (or adds to them). */
static int load_vectors(sweep_args *a, tb_sweep *s, vec_set *sets)
{
    if (a->nvec > 0 && !a->t.on && !a->derived) {
        if (!a->o.u->ref) return cli_usage_error("unit %s has no float reference model", a->o.u->name);
        for (size_t p = 0; p < s->npsets; p++) {
            vec_set_header(&sets[p], a->o.u->ref, &tb_sweep_pset_cfg(s, p)->model);
            s->vs[p] = &sets[p];
        }
        tb_sweep_stream(s, (size_t)a->nvec, a->seed);
        return 0;
    }
    /* a file named with --vectors (not stdin, one parameter set): each
     * configuration reads it a block at a time (the fingerprint reads it
     * first and refuses a bad one, before anything is written) */
    if (a->nvec <= 0 && a->o.vectors && strcmp(a->o.vectors, "-") && s->npsets == 1 && !a->t.on && !a->derived) {
        vec_set_init(&sets[0]);
        tb_expected_header(a->o.u, tb_sweep_pset_cfg(s, 0), &sets[0]);
        s->vs[0] = &sets[0];
        tb_sweep_stream_file(s, a->o.vectors);
        return 0;
    }
    for (size_t p = 0; p < s->npsets; p++) {
        cli_unit_opts o = a->o;
        o.cfg = *tb_sweep_pset_cfg(s, p);
        if (a->nvec > 0) {
            char err[600];
            if (tb_make_vectors(o.u, &o.cfg, (size_t)a->nvec, a->seed, &sets[p], err, sizeof err)) return cli_usage_error("%s", err);
        } else if (cli_load_vectors(&o, &sets[p])) {
            return CLI_USAGE;
        }
        s->vs[p] = &sets[p];
    }
    return sweep_ranges_stimuli(a, s, sets);
}

/* No silent widening: widths below what the unit's integer part needs
 * would all build the same formats; the sweep starts at the smallest
 * honest width and says so, once. */
static int sweep_min_width(sweep_args *a)
{
    int lim;
    unit_cfg limc;
    int wmin = tb_sweep_min_width(&a->sp, &lim, &limc);
    if (wmin <= a->sp.wlo) return 0;
    char why[200] = "";
    if (lim >= 0) {
        unit_fmts f;
        limc.width = wmin;
        a->o.u->formats(&limc, &f);
        snprintf(why, sizeof why, " (signal %s's integer part is %c%d)", a->o.u->sigs[lim].name,
                 f.f[lim].is_signed ? 's' : 'u', f.f[lim].ibits);
    }
    if (wmin > a->sp.whi)
        return cli_usage_error("--widths %d:%d: unit %s needs widths >= %d%s", a->sp.wlo, a->sp.whi, a->o.u->name, wmin, why);
    fprintf(stderr, "shadesim: sweep %s: widths below %d are too narrow for its integer part%s; starting at %d\n",
            a->o.u->name, wmin, why, wmin);
    a->sp.wlo = wmin;
    return 0;
}

/* A message per configuration that failed; the number that failed to
 * simulate. A configuration the unit cannot be built at (past the top of
 * its width range, say: shadesim list) is "not buildable", a row of the
 * results like any other, not a failed simulation. */
static size_t sweep_failures(const sweep_args *a, const tb_sweep *s, size_t failed)
{
    size_t unbuilt = 0;
    for (size_t i = 0; i < s->n; i++) {
        if (s->row[i].status == TB_OK || s->row[i].status == TB_SWEEP_NOT_RUN) continue;
        int nb = s->row[i].status == TB_BADINPUT;
        unbuilt += (size_t)nb;
        (void)cli_usage_error("%s width %d (configuration %zu)%s: %s", a->o.u->name, s->cfg[i].cfg.width, i,
                              nb ? " not buildable" : "", s->row[i].err);
    }
    return failed - unbuilt;
}

/* --shard K/N: the shard's rows as DIR/sweep-K-of-N.csv. */
static int sweep_shard_out(sweep_args *a, tb_sweep *s, int tty, double secs)
{
    char path[4200], err[600];
    snprintf(path, sizeof path, "%s/sweep-%d-of-%d.csv", a->dir, a->shard_k, a->shard_n);
    if (tb_sweep_write_csv(s, path, a->shard_k, a->shard_n, err, sizeof err)) return cli_usage_error("%s", err);
    size_t mine = 0;
    for (size_t i = 0; i < s->n; i++) mine += (size_t)tb_sweep_in_shard(i, a->shard_k, a->shard_n);
    printf("sweep %s shard %d/%d: %zu of %zu configurations, sweep_id %016llx\n", a->o.u->name,
           a->shard_k, a->shard_n, mine, s->n, (unsigned long long)s->id);
    sweep_print_accept(stdout, s, a->shard_k, a->shard_n, &a->misses);
    printf("wrote %s\n", path);
    if (tty) fprintf(stderr, "shadesim sweep %s: %.2f s\n", a->o.u->name, secs);
    return CLI_OK;
}

int cli_sweep(int argc, char **argv)
{
    if (cli_opt_help_wanted(argc, argv)) return cli_opt_help(&cli_sweep_spec);
    sweep_args a;
    if (sweep_parse(argc, argv, &a)) return CLI_USAGE;
    char defdir[300], err[600];
    if (!a.dir) {
        snprintf(defdir, sizeof defdir, "out/sweep-%s", a.o.u->name);
        a.dir = defdir;
    }
    tb_sweep s;
    if (sweep_min_width(&a)) return CLI_USAGE;
    if (tb_sweep_init(&s, &a.sp, err, sizeof err)) return cli_usage_error("%s", err);
    vec_set *sets = calloc(s.npsets, sizeof *sets);
    int rc = CLI_OK;
    if (!sets) base_out_of_memory();
    /* Everything that can be refused is refused before the long part. */
    if (load_vectors(&a, &s, sets)) { rc = CLI_USAGE; goto done; }
    if (tb_sweep_fingerprint(&s, err, sizeof err)) { rc = cli_usage_error("%s", err); goto done; }
    if (cli_make_dir(a.dir)) { rc = CLI_USAGE; goto done; }

    progress pr = { a.o.u->name, base_proc_now(), 0, 0 };
    int tty = cli_stderr_tty();
    size_t failed = tb_sweep_run(&s, a.threads, a.shard_k, a.shard_n, tty ? on_progress : NULL, &pr);
    progress_clear(&pr);
    double secs = base_proc_now() - pr.t0;
    failed = sweep_failures(&a, &s, failed);
    rc = a.shard_n ? sweep_shard_out(&a, &s, tty, secs) : sweep_outputs(&a, &s, pr.t0, tty);
    if (rc == CLI_OK && (failed || a.misses || a.ho_failed || a.t_missed)) rc = CLI_FAIL;
done:
    for (size_t p = 0; p < s.npsets; p++) vec_set_free(&sets[p]);
    free(sets);
    sweep_ranges_free(&a.t, s.ngroups);
    free(a.t.res);
    tb_sweep_free(&s);
    return rc == CLI_USAGE ? rc : cli_stdout_done(rc);
}
