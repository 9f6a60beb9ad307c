/* cli_run.c - `shadesim run`: a unit (or every unit) on its vectors,
 * checked, with its report. */
#include "testbench/cli/cli.h"
#include "testbench/cli/cli_opt.h"
#include "base/base_out.h"
#include "testbench/tb_stream.h"
#include "testbench/tb_wave.h"
#include "testbench/tb_widths.h"
#include "testbench/tb_derive.h"
#include "testbench/tb_netlist.h"
#include <limits.h>
#include <math.h>
#include <stddef.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

typedef struct run_args {
    const char *vcd, *csv;
    int json, fst, ranges, kernel, reference;
    long vfrom, vto;
    long nvec;              /* -n N: N generated vectors (0: the vector file) */
    int jobs;               /* -j N: the lanes' threads (default: one a core) */
    uint64_t seed;          /* --seed S of the generated vectors (default 1) */
    /* --ranges derived, --range NAME=LO:HI (static check) */
    int derived, nrange, want_mode;
    const unit_desc *u;
    tb_ranges rg;
} run_args;

/* --ranges [observed|derived]: alone (or observed), every signal's
 * observed range; derived, the static check. The mode may be the next
 * argument, which the parser hands to run_pos. */
static run_args *run_cur;
static int run_o_ranges(void *base, const char *opt, const char *val)
{
    run_args *ra = base;
    (void)opt;
    if (!val || !strcmp(val, "observed")) { ra->ranges = 1; ra->want_mode = !val; return 0; }
    if (!strcmp(val, "derived")) { ra->derived = 1; return 0; }
    return cli_usage_error("--ranges %s: expected observed or derived", val);
}

/* -j when not given: one thread a core online (the output is the same
 * for any -j), at most the option's own limit. */
static int run_default_jobs(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : n > 256 ? 256 : (int)n;
}

static int run_pos(void *base, const char *arg)
{
    (void)base;
    if (!run_cur || !run_cur->want_mode || (strcmp(arg, "derived") && strcmp(arg, "observed"))) return CLI_OPT_UNKNOWN;
    run_cur->want_mode = 0;
    if (!strcmp(arg, "derived")) { run_cur->derived = 1; run_cur->ranges = 0; }
    return 0;
}

static int run_o_range(void *base, const char *opt, const char *val)
{
    run_args *ra = base;
    char err[400];
    (void)opt;
    if (tb_ranges_parse(ra->u, val, &ra->rg, err, sizeof err)) return cli_usage_error("%s", err);
    ra->nrange++;
    return 0;
}

#define ACC_OPT(NAME, FIELD, HELP) { NAME, NULL, CLI_OPT_REAL, offsetof(tb_accept, FIELD), 0, 1e300, \
    "a positive number", "%s needs a number", NULL, CLI_OPT_GT_LO, HELP }
/* The acceptance options (run UNIT and run all). */
static const cli_opt accept_tab[] = {
    ACC_OPT("--max-error", max_error, "  --max-error E        target: max |hardware - expected| <= E\n"),
    ACC_OPT("--max-nmse", max_nmse, "  --max-nmse X         target: NMSE against the expected outputs <= X\n"),
    ACC_OPT("--max-lsb", max_lsb, "  --max-lsb K          target: max |hardware - expected| <= K output LSBs\n"),
    { "--allow-overflow", NULL, CLI_OPT_FLAG, offsetof(tb_accept, allow_overflow), 0, 0, NULL, NULL, NULL, 0,
      "  --allow-overflow     an overflow does not fail the verdict (it is still reported)\n" },
    { NULL, NULL, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL }
};

#define VCD_ITEM(NAME, FIELD, HELP) { NAME, NULL, CLI_OPT_LONG, offsetof(run_args, FIELD), 0, (double)LONG_MAX, \
    "an item number (0, 1, ...)", "%s needs an item number", NULL, 0, HELP }
static const cli_opt run_tab[] = {
    { "--ranges", NULL, CLI_OPT_CALL, 0, 0, 0, NULL, NULL, run_o_ranges, CLI_OPT_MAYBE,
      "  --ranges             list every signal's observed raw range, not only those that overflowed\n"
      "  --ranges derived     first check statically that every signal's format holds its\n"
      "                       interval for any input in the declared ranges (docs/sweeps.md)\n" },
    { "--range", NULL, CLI_OPT_CALL, 0, 0, 0, NULL, "%s : expected NAME=LO:HI", run_o_range, 0,
      "  --range NAME=LO:HI   an input's declared range for --ranges derived (default: its\n"
      "                       format's; repeatable)\n" },
    { "--json", NULL, CLI_OPT_FLAG, offsetof(run_args, json), 0, 0, NULL, NULL, NULL, 0,
      "  --json               print the result as one JSON object\n" },
    { "--out", NULL, CLI_OPT_STR, offsetof(run_args, csv), 0, 0, NULL, "%s needs a file name", NULL, 0,
      "  --out FILE.csv       one row per vector: index, cycle, NAME_raw/_real/_expected/_err\n" },
    { "--kernel", NULL, CLI_OPT_FLAG, offsetof(run_args, kernel), 0, 0, NULL, NULL, NULL, 0,
      "  --kernel             simulate on the event-driven kernel alone, and report its events,\n"
      "                       delta cycles and process runs (default: the batch's lanes where\n"
      "                       they give the same results; docs/batch.md; --vcd implies it)\n" },
    { "--no-batch", NULL, CLI_OPT_FLAG, offsetof(run_args, kernel), 0, 0, NULL, NULL, NULL, 0,
      "  --no-batch           the same as --kernel\n" },
    { "--reference", NULL, CLI_OPT_FLAG, offsetof(run_args, reference), 0, 0, NULL, NULL, NULL, 0,
      "  --reference          the kernel as its own reference: the plain evaluate/update loop,\n"
      "                       every element through its general evaluation, no logic tables,\n"
      "                       no clock-edge shortcut; the same results and counters as --kernel,\n"
      "                       slower (implies --kernel; docs/batch.md)\n" },
    { "--vcd", NULL, CLI_OPT_STR, offsetof(run_args, vcd), 0, 0, NULL, "%s needs a file name", NULL, 0,
      "  --vcd FILE           dump every register, mux, adder and multiplier (IEEE 1364 VCD)\n"
      "                       and each output beat's expected value and error (tb.expected_NAME,\n"
      "                       tb.err_NAME), with FILE.gtkw, a GTKWave save file: a group of the\n"
      "                       outputs with their expected values and errors, then one per unit,\n"
      "                       values in fixed point (docs/vcd.md)\n" },
    { "-n", NULL, CLI_OPT_LONG, offsetof(run_args, nvec), 1, 10000000, "1..10000000 vectors", NULL, NULL, 0,
      "  -n N                 instead of the vector file, N vectors made by the float\n"
      "                       reference (as shadesim vectors UNIT -n N makes them)\n" },
    { "-j", NULL, CLI_OPT_INT, offsetof(run_args, jobs), 1, 256, "1..256 threads", "%s needs a number of threads", NULL, 0,
      "  -j N                 threads of the lanes (default: the machine's cores); the\n"
      "                       output is the same for any N\n" },
    { "--seed", NULL, CLI_OPT_U64, offsetof(run_args, seed), 0, 0, "a whole number", NULL, NULL, 0,
      "  --seed S             seed of the -n vectors (default 1)\n" },
    VCD_ITEM("--vcd-from", vfrom,
      "  --vcd-from N, --vcd-to M  dump only items N..M (from 0, as --out's index): from the\n"
      "                       edge where item N is offered to the one that samples M's last beat\n"),
    VCD_ITEM("--vcd-to", vto, ""),
    { "--fst", NULL, CLI_OPT_FLAG, offsetof(run_args, fst), 0, 0, NULL, NULL, NULL, 0,
      "  --fst                FILE is an FST dump (GTKWave's compact format), converted by\n"
      "                       vcd2fst (Debian package gtkwave)\n" },
    { NULL, NULL, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL }
};

const cli_optspec cli_run_spec = {
    "run", { cli_unit_opt_tab, accept_tab, run_tab }, run_pos, 0,
    "run: unknown option '%s' (see shadesim run --help)",
    "usage: shadesim run UNIT [options]\n"
    "       shadesim run FILE [options]             a netlist file (shadesim netlist), built from its text\n"
    "       shadesim run all [acceptance options]   every unit on its default vectors, one summary table\n"
    "                                               (--json: each unit's run --json in one object)\n\n"
    "Drives UNIT clock by clock with golden vectors (inputs quantized to the unit's\n"
    "input formats with --round), reports cycles, area, quantization error and\n"
    "every signal's overflows, and gives a verdict (docs/bounds.md). Exit 0 when\n"
    "the verdict is ok: no signal overflowed, every output is within the error\n"
    "bound derived from the formats (checked exactly against the unit's ideal\n"
    "function of the quantized inputs), the golden check against the vector\n"
    "file's expected outputs holds, and your targets, if set, are met. Exit 1\n"
    "otherwise, also when the bound cannot be decided (\"unchecked\") or the unit\n"
    "derives none for the formats (\"no bound\") and no target is set: with no bound,\n"
    "your targets alone decide.\n\noptions:\n",
    "\nOutput files: a regular file is replaced only once complete (a symbolic link is\n"
    "followed and kept); a device or FIFO is written to in place. --out - or --vcd -\n"
    "writes that file to stdout (no .gtkw then) and the report goes to stderr; only\n"
    "one of --out -, --vcd - and --json can have stdout.\n"
};

/* run all: the acceptance options and --json. */
static const cli_opt run_all_tab[] = {
    { "--json", NULL, CLI_OPT_FLAG, 0, 0, 0, NULL, NULL, NULL, 0, "" },
    { NULL, NULL, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL }
};
static const cli_optspec run_all_spec = {
    "run all", { accept_tab, run_all_tab }, NULL, 0,
    "run all: unknown option '%s' (it takes --max-error, --max-nmse, --max-lsb, --allow-overflow, --json)", NULL, NULL
};

/* run all --json: {"units": [each unit's run --json object, in the
 * registry's order], "failed": units failing the bound or golden check,
 * "missed": units missing the target only, "verdict": "ok" or "fail"}. */
static int run_all(const tb_accept *acc, int json)
{
    int target = acc->max_error > 0 || acc->max_nmse > 0 || acc->max_lsb > 0;
    if (json) fputs("{\"units\": [\n", stdout);
    else printf("%-11s %-9s %6s %12s %12s %12s %10s %-9s %-8s %s\n", "unit", "schedule", "width", "clocks/item",
           "max|e|", "nmse", "area GE", "bound", "golden", target ? "target" : "method error");
    int rc = CLI_OK, bad = 0, missed = 0, emitted = 0;
    char far[400] = "";
    for (size_t i = 0, n = unit_count(); i < n; i++) {
        cli_unit_opts o;
        cli_unit_select(&o, unit_at(i)->name);
        vec_set vs;
        if (cli_load_vectors(&o, &vs)) { rc = CLI_USAGE; continue; }
        unit_fmts fm;
        char err[600];
        tb_result r;
        tb_formats(o.u, &o.cfg, NULL, 0, &fm, err, sizeof err);
        tb_opts lanes = { .lanes = 1 };
        int t = tb_run(o.u, &o.cfg, &fm, &vs, &lanes, &r, err, sizeof err);
        if (t != TB_OK) {
            rc = cli_from_tb(t, "%s: %s", o.u->name, err);
        } else {
            tb_verdict(&r, acc);
            double me = 0;
            for (int k = 0; k < r.n_out; k++) if (r.out[k].max_method_err > me) me = r.out[k].max_method_err;
            if (me > 1e-3 && strlen(far) < sizeof far - 40)
                snprintf(far + strlen(far), sizeof far - strlen(far), " %s (%.3g)", o.u->name, me);
            const char *bc = r.overflows && !acc->allow_overflow ? "OVERFLOW" : r.bound_check == TB_CHECK_OK ? "ok"
                           : r.bound_check == TB_CHECK_EXCEEDED ? "EXCEEDED" : r.bound_check == TB_CHECK_NO_BOUND ? "NO BOUND" : "UNCHECKED";
            char last[32];
            if (target) snprintf(last, sizeof last, "%s", r.target_met ? "met" : "MISSED");
            else snprintf(last, sizeof last, "%.3g", me);
            if (json) {
                if (emitted++) fputs(",\n", stdout);
                tb_write_json(stdout, &r);
            } else printf("%-11s %-9s %6d %12.4g %12.4g %12.4g %10.1f %-9s %-8s %s\n", o.u->name, o.u->sched[o.cfg.schedule].name,
                   o.cfg.width, r.cycles_per_item, isnan(r.max_abs_err) ? NAN : r.max_abs_err,
                   isnan(r.nmse) ? NAN : r.nmse, r.area_ge, bc, r.golden_ok ? "ok" : "EXCEEDED", last);
            if (!r.ok) {
                if (r.target_set && !r.target_met && r.within_bound && r.golden_ok) missed++;
                else bad++;
                if (rc == CLI_OK) rc = CLI_FAIL;
            }
        }
        tb_result_free(&r);
        vec_set_free(&vs);
    }
    if (json) {
        printf("],\n\"failed\": %d, \"missed\": %d, \"verdict\": \"%s\"}\n", bad, missed, rc == CLI_OK ? "ok" : "fail");
        return cli_stdout_done(rc);
    }
    printf("\nbound ok: no overflow and every output within the bound derived from its formats, checked\n"
           "against the unit's ideal function (exactly; units whose ideal is only a double: to 2^-40\n"
           "relative, else \"unchecked\"); golden ok: within that bound plus input rounding\n"
           "plus the method's own approximation of the true function. max|e| is against the true\n"
           "function: a unit can be within its bound and far from it (interp3's 3-term 1/3).\n%s\n",
           target ? "target: your --max-error / --max-nmse / --max-lsb." :
           "method error: how far the unit's ideal is from the true function; no target set\n"
           "(--max-error, --max-nmse, --max-lsb make a miss fail the run).");
    if (bad) printf("summary: %d unit(s) fail the derived-bound or golden check\n", bad);
    else printf("summary: every unit within its derived bound and golden check\n");
    if (far[0]) printf("summary: within their bound but far from the true function (method error > 1e-3):%s\n", far);
    if (target) printf("summary: %s\n", missed ? "some units MISS your target" : "every unit meets your target");
    return cli_stdout_done(rc);
}

/* run --ranges derived: every signal's interval for inputs in the
 * declared ranges against its format, before any vector. The number of
 * formats that cannot hold their interval (0 when all can), -1 after a
 * message.
 * With --json, opens the object the run's result is a member of. */
static int check_derived(const cli_unit_opts *o, const unit_fmts *fm, const tb_ranges *rg, int json, FILE *report)
{
    tb_derived d;
    char err[600];
    if (tb_derive(o->u, &o->cfg, fm, rg, &d, err, sizeof err)) { cli_usage_error("%s", err); return -1; }
    if (json) {
        printf("{\"ranges_derived\": {\"ok\": %s, \"cannot_hold\": %d, \"signals\": ", d.nfail ? "false" : "true", d.nfail);
        tb_derived_json(stdout, &d, NULL);
        fputs("},\n\"run\": ", stdout);
    } else if (d.nfail) {
        fprintf(report, "ranges derived: %d signal(s) CANNOT HOLD their interval for inputs in the declared ranges:\n",
                d.nfail);
        tb_derived_print(report, &d, NULL, 0);
    } else {
        fprintf(report, "ranges derived: ok: every signal's format holds its interval for inputs in the declared ranges\n");
    }
    int bad = d.nfail;
    tb_derived_free(&d);
    return bad;
}

/* A run whose formats cannot hold the derived ranges (check_derived's
 * count) does not pass, whatever its vectors showed: the verdict says so,
 * in the table and the JSON alike, as the exit status does. */
static void derived_verdict(tb_result *r, int nbad)
{
    if (nbad <= 0 || !r->ok) return;
    r->ok = 0;
    snprintf(r->why, sizeof r->why,
             "CANNOT HOLD: %d signal(s) can leave their format for inputs in the declared ranges (--ranges derived)",
             nbad);
}

static void csv_row(void *data, const tb_result *r, size_t idx, uint64_t cycle, const int64_t *raw,
                    const double *expected)
{
    tb_csv_row(base_out_file(data), r, idx, cycle, raw, expected);
}

/* An output written in place (stdout, a device, a FIFO): rows written to
 * it cannot be taken back. */
static int written_in_place(const char *path)
{
    struct stat st;
    return !strcmp(path, "-") || (!stat(path, &st) && !S_ISREG(st.st_mode));
}

/* The --out file with its header: NULL after the message. */
static base_out *csv_open(const char *csv, const vec_set *hdr)
{
    char err[600];
    base_out *out = base_out_open(csv, err, sizeof err);
    if (!out) { cli_usage_error("%s", err); return NULL; }
    tb_csv_header(base_out_file(out), hdr->n_out, (const char (*)[16])hdr->out_names);
    return out;
}

/* run UNIT on a vector file or pipe, streamed: on the batch's lanes
 * (tb_run_stream_lanes, threads > 0) or the kernel (tb_run_stream), the
 * same report, --out rows written as items complete. The header and first
 * rows are read first, so a bad file is reported before anything is
 * written. When the lanes do not take the stream, the kernel runs it from
 * its first row: handed back unread (the lanes stopped in its first
 * block), or the file opened again; a pipe read past its first block
 * cannot be, and says so. */
static int run_streamed(const cli_unit_opts *o, const unit_fmts *fm, const char *path, const char *csv,
                        int json, int ranges, int reference, int threads, FILE *report, const tb_accept *acc,
                        const char *why, int static_bad)
{
    char err[600];
    vec_set hdr;
    vec_set_init(&hdr);
    tb_expected_header(o->u, &o->cfg, &hdr);
    vec_stream *vs = vec_stream_open(path, &hdr, err, sizeof err);
    if (!vs) return cli_usage_error("%s", err);
    const vec_set *rows;
    if (vec_stream_next(vs, &rows) < 0) {
        cli_usage_error("%s", vec_stream_error(vs));
        vec_stream_close(vs);
        return CLI_USAGE;
    }
    vec_stream_unread(vs);
    base_out *out = NULL;
    if (csv && !(out = csv_open(csv, &hdr))) { vec_stream_close(vs); return CLI_USAGE; }
    tb_result r;
    tb_opts topt = { .reference = reference };
    char lwhy[160] = "";
    int t = TB_STREAM_KERNEL, rewound = 1;
    if (threads) {
        t = tb_run_stream_lanes(o->u, &o->cfg, fm, vs, csv ? csv_row : NULL, out, threads, &r, &rewound, err, sizeof err);
        if (t == TB_STREAM_KERNEL) {
            snprintf(lwhy, sizeof lwhy, "%s", r.engine_why);
            tb_result_free(&r);
            why = lwhy;
            if (!rewound && ((csv && written_in_place(csv)) || written_in_place(path))) {
                if (out) base_out_abort(out);
                vec_stream_close(vs);
                if (written_in_place(path))
                    return cli_usage_error("run: the lanes stopped (%s) past the first block of %s, which cannot be "
                                           "read again for the kernel: run it with --kernel", lwhy,
                                           strcmp(path, "-") ? path : "stdin");
                return cli_usage_error("run: the lanes stopped (%s) after rows went to --out %s, which cannot take "
                                       "them again: run it with --kernel", lwhy, csv);
            }
            if (out) { base_out_abort(out); out = NULL; }
            if (csv && !(out = csv_open(csv, &hdr))) { vec_stream_close(vs); return CLI_USAGE; }
            if (!rewound) {
                vec_stream_close(vs);
                if (!(vs = vec_stream_open(path, &hdr, err, sizeof err))) {
                    if (out) base_out_abort(out);
                    return cli_usage_error("%s", err);
                }
            }
        }
    }
    if (t == TB_STREAM_KERNEL)
        t = tb_run_stream(o->u, &o->cfg, fm, vs, csv ? csv_row : NULL, out, &topt, &r, err, sizeof err);
    vec_stream_close(vs);
    int rc = CLI_OK;
    if (t != TB_OK) {
        if (out) base_out_abort(out);
        rc = cli_from_tb(t, "%s", err);
    } else {
        if (out && base_out_close(out, err, sizeof err)) rc = cli_usage_error("%s", err);
        tb_verdict(&r, acc);
        derived_verdict(&r, static_bad);
        if (why) snprintf(r.engine_why, sizeof r.engine_why, "%s", why);
        if (json) tb_write_json(stdout, &r);
        else {
            tb_print_table(report, &r);
            if (ranges) tb_print_ranges(report, &r, 1);
        }
        if (rc == CLI_OK && !r.ok) rc = CLI_FAIL;
    }
    tb_result_free(&r);
    return rc == CLI_USAGE ? rc : cli_stdout_done(rc);
}

/* Options that go together, or exclude each other: 0, or CLI_USAGE
 * after the message. */
static int options_clash(const run_args *ra, const cli_unit_opts *o)
{
    if (ra->nrange && !ra->derived) return cli_usage_error("run: --range goes with --ranges derived");
    if (ra->nvec && o->vectors) return cli_usage_error("run: -n makes the vectors; --vectors reads them: give one");
    if (ra->seed != 1 && !ra->nvec) return cli_usage_error("run: --seed goes with -n");
    const char *vcd = ra->vcd;
    long long vfrom = ra->vfrom, vto = ra->vto;
    /* "-" is stdout for each output option; stdout holds one stream. */
    int vcd_out = vcd && !strcmp(vcd, "-"), csv_out = ra->csv && !strcmp(ra->csv, "-");
    if (vcd_out + csv_out + ra->json > 1)
        return cli_usage_error("run: only one of --out -, --vcd - and --json can write to stdout");
    if ((vfrom >= 0 || vto >= 0 || ra->fst) && !vcd)
        return cli_usage_error("run: %s needs --vcd FILE", ra->fst ? "--fst" : vfrom >= 0 ? "--vcd-from" : "--vcd-to");
    if (vfrom >= 0 && vto >= 0 && vfrom > vto)
        return cli_usage_error("run: --vcd-from %lld is after --vcd-to %lld", vfrom, vto);
    if (ra->fst && vcd_out) return cli_usage_error("run: --fst needs a file, not --vcd -");
    if (ra->fst && !tb_wave_have_vcd2fst())
        return cli_usage_error("run: --fst needs vcd2fst, which is not installed (Debian package gtkwave)");
    return 0;
}

int cli_run(int argc, char **argv)
{
    cli_unit_opts o;
    if (cli_opt_help_wanted(argc, argv)) return cli_opt_help(&cli_run_spec);
    if (argc < 2 || argv[1][0] == '-') return cli_usage_error("run: which unit? (shadesim list, a netlist file, or run all)");
    const char *unit = argv[1];
    tb_accept acc = { 0 };
    if (!strcmp(unit, "all")) {
        int json = 0;
        void *base[] = { &acc, &json };
        if (cli_opt_parse(&run_all_spec, base, argc, argv, 2)) return CLI_USAGE;
        return run_all(&acc, json);
    }
    /* A name that is no unit but a file's: a netlist (shadesim netlist),
     * built from its text, run against the unit it names; or a datapath
     * file (docs/datapaths.md). */
    struct stat nst;
    unit_cfg ncfg;
    unit_fmts fm;
    char err[600];
    const unit_desc *nlu = NULL;
    if (!unit_find(unit) && !stat(unit, &nst)) {
        if (!(nlu = tb_netlist_load(unit, &ncfg, &fm, err, sizeof err))) return cli_usage_error("%s", err);
        o = (cli_unit_opts){ .u = nlu, .cfg = ncfg };
        if (tb_datapath_is(nlu)) nlu = NULL;   /* a datapath file: a unit of its own, --width... apply */
    } else if (cli_unit_select(&o, unit)) return CLI_USAGE;
    run_args ra = { NULL, NULL, 0, 0, 0, 0, 0, -1, -1, 0, run_default_jobs(), 1, 0, 0, 0, NULL, { { 0 }, { 0 }, { 0 } } };
    ra.u = o.u;
    run_cur = &ra;
    void *base[] = { &o, &acc, &ra };
    int bad = cli_opt_parse(&cli_run_spec, base, argc, argv, 2);
    run_cur = NULL;
    if (bad) return CLI_USAGE;
    if (nlu && (o.nfmt || memcmp(&o.cfg, &ncfg, sizeof ncfg)))
        return cli_usage_error("run %s: the netlist is the design: --width, --fmt, --round, --overflow, --schedule "
                               "and --param are its own lines (write it again with shadesim netlist %s ...)",
                               unit, o.u->name);
    if (options_clash(&ra, &o)) return CLI_USAGE;
    const char *vcd = ra.vcd, *csv = ra.csv;
    int json = ra.json, fst = ra.fst, ranges = ra.ranges;
    long long vfrom = ra.vfrom, vto = ra.vto;
    int vcd_out = vcd && !strcmp(vcd, "-"), csv_out = csv && !strcmp(csv, "-");
    FILE *report = vcd_out || csv_out ? stderr : stdout;
    if (!nlu && tb_formats(o.u, &o.cfg, o.fmt, o.nfmt, &fm, err, sizeof err)) return cli_usage_error("%s", err);
    if (!o.nfmt && !nlu) {
        /* Past the top of the unit's range the build would refuse with a
         * hint about one signal; say the range instead (shadesim list). */
        if (tb_width_refuse(o.u, &o.cfg, err, sizeof err)) return cli_usage_error("--width %d: %s", o.cfg.width, err);
    }
    int static_bad = 0;
    if (ra.derived && (static_bad = check_derived(&o, &fm, &ra.rg, json, report)) < 0) return CLI_USAGE;
    /* Without a dump, a vector file (or pipe) is read a block at a time,
     * on the lanes or the kernel: memory does not grow with the number of
     * vectors (docs/batch.md). */
    int lanes = !ra.kernel && !ra.reference && !vcd;
    char vpath[4200];
    const char *vfile = NULL;
    if (!vcd && !ra.nvec) {
        int f = cli_vectors_file(&o, vpath, sizeof vpath, &vfile);
        if (f < 0) return CLI_USAGE;
        if (f) {
            int rs = run_streamed(&o, &fm, vfile, csv, json, ranges, ra.reference, lanes ? ra.jobs : 0, report, &acc,
                                  NULL, static_bad);
            if (json && ra.derived) fputs("}\n", stdout);
            return rs == CLI_OK && static_bad ? cli_stdout_done(CLI_FAIL) : rs;
        }
    }
    vec_set vs;
    if (ra.nvec) {
        if (tb_make_vectors(o.u, &o.cfg, (size_t)ra.nvec, ra.seed, &vs, err, sizeof err)) return cli_usage_error("%s", err);
    } else if (cli_load_vectors(&o, &vs)) return CLI_USAGE;
    tb_opts opts = { .vcd_path = vcd, .gtkw = !vcd_out, .fst = fst, .lanes = lanes, .reference = ra.reference,
                     .threads = ra.jobs };
    if (vfrom >= 0 || vto >= 0) {
        int bad_from = vfrom >= 0 && (size_t)vfrom >= vs.n_rows;
        if (bad_from || (vto >= 0 && (size_t)vto >= vs.n_rows)) {
            size_t n = vs.n_rows;
            vec_set_free(&vs);
            return cli_usage_error("run: --vcd-%s %lld: the vectors have %zu items (0..%zu)", bad_from ? "from" : "to",
                                   bad_from ? vfrom : vto, n, n ? n - 1 : 0);
        }
        opts.vcd_window = 1;
        opts.vcd_from = vfrom >= 0 ? (size_t)vfrom : 0;
        opts.vcd_to = vto >= 0 ? (size_t)vto : vs.n_rows - 1;
    }
    tb_result r;
    int t = tb_run(o.u, &o.cfg, &fm, &vs, &opts, &r, err, sizeof err);
    int rc = CLI_OK;
    if (t != TB_OK) {
        /* The vectors' header was checked when they were read, so this is
         * about the unit (formats it cannot build with) or an output file. */
        rc = cli_from_tb(t, "%s", err);
    } else {
        if (csv && tb_write_csv(csv, &r, &vs, err, sizeof err)) rc = cli_usage_error("%s", err);
        tb_verdict(&r, &acc);
        derived_verdict(&r, static_bad);
        if (json) tb_write_json(stdout, &r);
        else {
            tb_print_table(report, &r);
            if (ranges) tb_print_ranges(report, &r, 1);
        }
        if (rc == CLI_OK && !r.ok) rc = CLI_FAIL;
    }
    tb_result_free(&r);
    vec_set_free(&vs);
    if (json && ra.derived) fputs("}\n", stdout);
    if (rc == CLI_OK && static_bad) rc = CLI_FAIL;
    return rc == CLI_USAGE ? rc : cli_stdout_done(rc);
}
