/* cli_merge.c - the verb merge: a sharded sweep's CSVs joined into the
 * whole sweep's (tb_sweep_merge). */
#include "testbench/cli/cli.h"
#include "testbench/cli/cli_opt.h"
#include "testbench/study/tb_sweep.h"
#include "base/base_out.h"
#include <stddef.h>
#include <stdlib.h>

typedef struct merge_args {
    const char *out;
    const char **in;        /* [argc] */
    int n;
} merge_args;

static int merge_file(void *base, const char *arg)
{
    merge_args *m = base;
    m->in[m->n++] = arg;
    return 0;
}

static const cli_opt merge_tab[] = {
    { "-o", NULL, CLI_OPT_STR, offsetof(merge_args, out), 0, 0, NULL, "-o needs a file name", NULL, CLI_OPT_NONEMPTY, NULL },
    { NULL, NULL, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL }
};

const cli_optspec cli_merge_spec = {
    "merge", { merge_tab }, merge_file, 1, "merge: unknown option '%s' (see shadesim merge --help)",
    "usage: shadesim merge SHARD.csv ... -o OUT.csv\n\n"
    "Joins the CSVs of a sweep's shards (shadesim sweep --shard K/N) into exactly\n"
    "the sweep.csv that the whole sweep writes: rows back in configuration order.\n"
    "The headers must be identical and the rows of one sweep (same sweep_id);\n"
    "a configuration given twice or missing is an error (exit status 2).\n"
    "-o - writes to stdout; an existing OUT.csv is replaced only once complete\n"
    "(a symbolic link is followed and kept; a device or FIFO is written to in place).\n", NULL
};

int cli_merge(int argc, char **argv)
{
    if (cli_opt_help_wanted(argc, argv)) return cli_opt_help(&cli_merge_spec);
    merge_args m = { NULL, calloc((size_t)argc, sizeof *m.in), 0 };
    if (!m.in) base_out_of_memory();
    void *base[] = { &m };
    int rc = cli_opt_parse(&cli_merge_spec, base, argc, argv, 1);
    char err[800];
    if (rc) rc = CLI_USAGE;
    else if (!m.n) rc = cli_usage_error("merge: which CSV files? (shadesim merge A.csv B.csv -o OUT.csv)");
    else if (!m.out) rc = cli_usage_error("merge: -o OUT.csv is required");
    else if (tb_sweep_merge(m.in, m.n, m.out, err, sizeof err)) rc = cli_usage_error("%s", err);
    free(m.in);
    if (rc == CLI_OK && base_out_stdout_check(err, sizeof err)) rc = cli_usage_error("%s", err);
    return rc;
}
