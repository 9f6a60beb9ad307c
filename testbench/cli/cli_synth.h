/* cli_synth.h - the synth verb's options (parsed in cli_verilog.c) and its
 * two real flows, --sta and --fpga (cli_synth.c), which print what the
 * tools measured beside the model's figures. */
#ifndef CLI_SYNTH_H
#define CLI_SYNTH_H
#include "testbench/cli/cli.h"

typedef struct cli_synth_st {
    const char *keep;
    int sta, json;
    const char *liberty;        /* --liberty FILE */
    double clock_ps;            /* --clock-ps (0: 10000) */
    const char *fpga, *device, *package;   /* --fpga ice40 --device hx8k --package ct256 */
    double freq_mhz;            /* --freq (0: nextpnr's default) */
    double timeout_s;           /* --timeout (-1: 600; 0: none) */
    int abc;                    /* --abc: CLI_SYNTH_ABC_* (-1: not given, auto) */
} cli_synth_st;

#define CLI_SYNTH_TIMEOUT 600
/* --abc auto (0), full, light; auto takes the light script past
 * TB_ABC_LIGHT_GE of the model's area (tb_abc_auto; docs/timing.md, "Big
 * designs") */
enum { CLI_SYNTH_ABC_AUTO = 0, CLI_SYNTH_ABC_FULL, CLI_SYNTH_ABC_LIGHT };

/* The folder the flow works in: --keep DIR (made), else a temporary one
 * in $TMPDIR (else /tmp), its name in tmpl. NULL after the message
 * (CLI_USAGE). */
const char *cli_synth_dir(const cli_synth_st *st, char *tmpl, size_t len);
/* The flow's end: the temporary folder removed (not --keep), and after
 * a signal shadesim dies by it. */
void cli_synth_cleanup(const cli_synth_st *st, const char *dir, int signal);
/* synth --sta / --fpga: the exit status. */
int cli_synth_flow(const cli_unit_opts *o, const unit_fmts *fm, const cli_synth_st *st);
#endif
