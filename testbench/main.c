/* main.c - bin/shadesim: dispatch to a verb. */
#include "testbench/cli.h"
#include "sim/sim_out.h"
#include <string.h>

const cli_verb cli_verbs[] = {
    { "list",    cli_list,    "units, schedules, signals, parameters and default formats" },
    { "vectors", cli_vectors, "golden vectors of a unit from the float reference" },
    { "run",     cli_run,     "run a unit's testbench: cycles, area, quantization error" },
    { "claims",  cli_claims,  "each numerical claim of the seeds next to what we measure" },
    { "sweep",   cli_sweep,   "a unit over bit widths and settings: CSV, charts, Pareto front, target search" },
    { "scene",   cli_scene,   "render a scene through the simulated interpolation hardware: images, NMSE, clocks, area" },
    { "verilog", cli_verilog, "a unit as synthesizable Verilog-2001, bit-exact with the simulation, and its testbench" },
    { "cosim",   cli_cosim,   "the exported Verilog in Icarus or Verilator against shadesim, raw for raw, cycle for cycle" },
    { "synth",   cli_synth,   "Yosys cell counts of the exported Verilog beside shadesim's area estimate" },
    { "merge",   cli_merge,   "join the CSVs of a sharded sweep into the whole sweep's CSV" },
    { NULL, NULL, NULL }
};

static void usage(FILE *f)
{
    fputs("usage: shadesim VERB [options]   (shadesim VERB --help for each)\n\n"
          "A cycle-accurate fixed-point simulator of the shading hardware in shared/seeds.\n\nverbs:\n", f);
    for (const cli_verb *v = cli_verbs; v->name; v++) fprintf(f, "  %-9s %s\n", v->name, v->summary);
    fputs("\nexit status: 0 success, 1 error bound exceeded or simulation failed, 2 bad usage or input\n", f);
}

int main(int argc, char **argv)
{
    sim_out_install_signals();  /* temporaries removed on SIGINT/TERM/HUP */
    if (argc < 2) return cli_usage_error("no verb given (shadesim --help lists them)");
    if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h") || !strcmp(argv[1], "help")) { usage(stdout); return CLI_OK; }
    for (const cli_verb *v = cli_verbs; v->name; v++)
        if (!strcmp(argv[1], v->name)) return v->fn(argc - 1, argv + 1);
    return cli_usage_error("unknown verb '%s' (try shadesim --help)", argv[1]);
}
