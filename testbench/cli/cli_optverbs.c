/* cli_optverbs.c - every verb's option tables in one list (cli_opt.h), so
 * that a test can hold each verb's --help to its tables. */
#include "testbench/cli/cli.h"
#include "testbench/cli/cli_opt.h"

const cli_optverb cli_optverbs[] = {
    { &cli_list_spec, cli_list },
    { &cli_vectors_spec, cli_vectors },
    { &cli_run_spec, cli_run },
    { &cli_claims_spec, cli_claims },
    { &cli_sweep_spec, cli_sweep },
    { &cli_scene_spec, cli_scene },
    { &cli_verilog_spec, cli_verilog },
    { &cli_cosim_spec, cli_cosim },
    { &cli_synth_spec, cli_synth },
    { &cli_netlist_spec, cli_netlist },
    { &cli_stability_spec, cli_stability },
    { &cli_factor_spec, cli_factor },
    { &cli_merge_spec, cli_merge },
    { &cli_chart_spec, cli_chart },
    { &cli_report_spec, cli_report },
    { NULL, NULL }
};
