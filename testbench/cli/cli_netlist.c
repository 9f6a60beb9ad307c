/* cli_netlist.c - `shadesim netlist`: a unit as built, as text
 * (tb_netlist.h, docs/netlist.md), which `run FILE` builds back. */
#include "testbench/cli/cli.h"
#include "testbench/cli/cli_opt.h"
#include "testbench/tb_netlist.h"
#include "base/base_out.h"
#include <stddef.h>
#include <string.h>

typedef struct netlist_st { const char *out; int dp; } netlist_st;

/* UNIT, the first argument that is not an option. */
static int unit_arg(void *base, const char *arg)
{
    cli_unit_opts *o = base;
    if (o->u) return CLI_OPT_UNKNOWN;
    return cli_unit_select(o, arg);
}

static int set_param(void *base, const char *opt, const char *v)
{
    return ((cli_unit_opts *)base)->u ? cli_unit_param(base, opt, v) : CLI_OPT_UNKNOWN;
}

static const cli_opt netlist_tab[] = {
    { "-o", NULL, CLI_OPT_STR, offsetof(netlist_st, out), 0, 0, NULL, "%s needs a file", NULL, CLI_OPT_NONEMPTY,
      "  -o FILE              write the text to FILE (default: standard output)\n" },
    { "--datapath", NULL, CLI_OPT_FLAG, offsetof(netlist_st, dp), 0, 0, NULL, NULL, NULL, 0,
      "  --datapath           write it as a datapath file (docs/datapaths.md) that names the unit\n"
      "                       for its reference (ideal unit=UNIT): formats as rules of W where\n"
      "                       they follow the width, the control as schedule rows where it is\n"
      "                       the step counter the reader makes; every verb takes the file\n" },
    { NULL, NULL, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL }
};

/* --set NAME=VALUE: --param's other spelling. */
static const cli_opt set_tab[] = {
    { "--set", NULL, CLI_OPT_CALL, 0, 0, 0, NULL, "%s needs NAME=VALUE", set_param, 0,
      "  --set NAME=VALUE     the same as --param NAME=VALUE\n" },
    { NULL, NULL, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL }
};

static const cli_opt no_opts[] = { { NULL, NULL, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL } };

const cli_optspec cli_netlist_spec = {
    "netlist", { no_opts, netlist_tab, cli_unit_opt_tab, set_tab }, unit_arg, 0,
    "netlist: unexpected argument '%s' (see shadesim netlist --help)",
    "usage: shadesim netlist UNIT [options] [--datapath] [-o FILE]\n"
    "Write the unit as shadesim builds it (same formats, modes, schedule and\n"
    "handshake) as text: its configuration, clock and scopes, one line per\n"
    "signal in the order built (inputs, constants, registers with enable and\n"
    "reset, multiplexers, block keys, adders, subtractors, multipliers, shifts,\n"
    "logic as truth tables), then its ports (docs/netlist.md). `shadesim run FILE`\n"
    "builds the design back from the text and runs it on the unit's vectors, with\n"
    "the same results as `shadesim run UNIT`. The bytes depend only on the options.\n"
    "options:\n",
    "\nThe file is replaced only once complete (a symbolic link is followed and kept;\n"
    "a device or FIFO is written to in place).\n"
};

int cli_netlist(int argc, char **argv)
{
    if (cli_opt_help_wanted(argc, argv)) return cli_opt_help(&cli_netlist_spec);
    cli_unit_opts o;
    netlist_st st = { NULL, 0 };
    memset(&o, 0, sizeof o);
    void *base[] = { &o, &st, &o, &o };
    if (cli_opt_parse(&cli_netlist_spec, base, argc, argv, 1)) return CLI_USAGE;
    if (!o.u) return cli_usage_error("netlist: no unit given (shadesim list shows the units)");
    if (o.vectors) return cli_usage_error("netlist: --vectors is run's: a netlist holds the design, not its vectors");
    if (tb_datapath_is(o.u))
        return cli_usage_error("netlist: %s is a datapath file, already the design's text (docs/datapaths.md)", o.u->source);
    char err[600];
    base_out *out = base_out_open(st.out ? st.out : "-", err, sizeof err);
    if (!out) return cli_usage_error("%s", err);
    if ((st.dp ? tb_netlist_write_dp : tb_netlist_write)(base_out_file(out), o.u, &o.cfg, o.fmt, o.nfmt, err, sizeof err)) {
        base_out_abort(out);
        return cli_usage_error("netlist %s: %s", o.u->name, err);
    }
    if (base_out_close(out, err, sizeof err)) return cli_usage_error("%s", err);
    return st.out ? CLI_OK : cli_stdout_done(CLI_OK);
}
