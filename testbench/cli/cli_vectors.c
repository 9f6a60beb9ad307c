/* cli_vectors.c - `shadesim vectors`: golden vectors of a unit from its
 * float reference. */
#include "testbench/cli/cli.h"
#include "testbench/cli/cli_opt.h"
#include "testbench/tb_stream.h"
#include "vectors/vec_file.h"
#include <stddef.h>
#include <string.h>

typedef struct vectors_args {
    cli_unit_opts o;        /* the unit, and --param once it is chosen */
    const char *unit, *out;
    long n;
    uint64_t seed;
} vectors_args;

static int vectors_unit_arg(void *base, const char *arg)
{
    vectors_args *va = base;
    if (va->unit) return CLI_OPT_UNKNOWN;
    va->unit = arg;
    return cli_unit_select(&va->o, arg);
}

static const cli_opt vectors_tab[] = {
    { "-n", NULL, CLI_OPT_LONG, offsetof(vectors_args, n), 0, 10000000, NULL, NULL, NULL, 0, NULL },
    { "--seed", NULL, CLI_OPT_U64, offsetof(vectors_args, seed), 0, 0, NULL, NULL, NULL, 0, NULL },
    { "-o", NULL, CLI_OPT_STR, offsetof(vectors_args, out), 0, 0, NULL, "-o needs a FILE", NULL, 0, NULL },
    { NULL, NULL, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL }
};
static const cli_opt vectors_param_tab[] = {
    { "--param", NULL, CLI_OPT_CALL, 0, 0, 0, NULL, NULL, cli_unit_param, 0, NULL },
    { NULL, NULL, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL }
};

const cli_optspec cli_vectors_spec = {
    "vectors", { vectors_tab, vectors_param_tab }, vectors_unit_arg, 0,
    "vectors: unexpected argument '%s' (see shadesim vectors --help)",
    "usage: shadesim vectors UNIT [-n N] [--seed S] [--param NAME=VALUE ...] [-o FILE]\n\n"
    "Golden vectors for UNIT from the double-precision float reference, in the\n"
    "text vector format (stdout, or FILE written atomically). With the default\n"
    "N (0: the unit's default set) and seed 1 this is the checked-in\n"
    "vectors/UNIT.vec.\n\n"
    "-o FILE: a regular file is replaced only once complete (a symbolic link is\n"
    "followed and kept); a device or FIFO is written to in place; -o - is stdout.\n", NULL
};

int cli_vectors(int argc, char **argv)
{
    if (cli_opt_help_wanted(argc, argv)) return cli_opt_help(&cli_vectors_spec);
    vectors_args va;
    memset(&va, 0, sizeof va);
    va.seed = 1;
    void *base[] = { &va, &va.o };
    if (cli_opt_parse(&cli_vectors_spec, base, argc, argv, 1)) return CLI_USAGE;
    cli_unit_opts o = va.o;
    const char *unit = va.unit, *out = va.out;
    long n = va.n;
    uint64_t seed = va.seed;
    if (!unit) return cli_usage_error("vectors: which unit? (shadesim list)");
    vec_set vs;
    char err[600];
    if (tb_make_vectors(o.u, &o.cfg, (size_t)n, seed, &vs, err, sizeof err)) return cli_usage_error("%s", err);
    int rc = CLI_OK;
    /* "-" (and no -o) is stdout, checked for write errors like a file. */
    if (vec_file_write(out ? out : "-", &vs, err, sizeof err)) rc = cli_usage_error("%s", err);
    vec_set_free(&vs);
    return rc == CLI_OK ? cli_stdout_done(rc) : rc;
}

