/* sim_vcd.h - IEEE 1364-2005 section 18 value change dump.
 *
 * The writer dumps every signal of the design (clock included) as a
 * `$var wire` of its width inside one `$scope module` per sim_scope, then
 * `$dumpvars` with the initial values and, at each time step, only the
 * signals whose value differs from what was last dumped. It watches the
 * run as a kernel observer (sim_observe): the kernel knows nothing of it.
 *
 * It writes to a stream its caller opened and closes: where the bytes go
 * (a temporary renamed into place, a device, standard output) is the
 * caller's business. After a simulation error, sim_vcd_close still ends
 * the dump properly: what was dumped up to the error is a complete file.
 */
#ifndef SIM_VCD_H
#define SIM_VCD_H
#include "sim/sim.h"

typedef struct sim_vcd sim_vcd;

/* Dump c's run into f (opened for writing by the caller; never closed
 * here), timescale like "1ns". Every signal of the design must exist by
 * now (later ones are not dumped). NULL when out of memory. The header is
 * written with the first time step (or at close), so that real variables
 * can be declared between open and the run. */
sim_vcd *sim_vcd_open(sim_ctx *c, FILE *f, const char *timescale);

/* A real-valued variable (IEEE 1364 `$var real 64`) in scope `scope`
 * under the root, e.g. a testbench's expected values; before the run.
 * Its index, or -1 (out of memory, or the header is already written). */
int      sim_vcd_add_real(sim_vcd *v, const char *scope, const char *name);
/* Its value from the time step being dumped on (initially 0). */
void     sim_vcd_set_real(sim_vcd *v, int idx, double value);
/* Called at every time step, before it is written, with every signal
 * settled: where a testbench sets real variables and the window. */
typedef void (*sim_vcd_hook)(sim_vcd *v, sim_time t, void *data);
void     sim_vcd_on_step(sim_vcd *v, sim_vcd_hook fn, void *data);
/* A time window. SIM_VCD_WRITE (the default): steps are written;
 * SIM_VCD_HOLD: they are not (the first step written after a hold writes
 * what changed meanwhile, or $dumpvars with every value if it is the first
 * step written at all); SIM_VCD_LAST: this step is written, then HOLD. */
enum { SIM_VCD_WRITE = 0, SIM_VCD_HOLD, SIM_VCD_LAST };
void     sim_vcd_window(sim_vcd *v, int mode);
/* Write what is left (the header, if no step was), stop watching the run
 * and free v; the stream stays open. 0, or -1 when a write failed (errno
 * from the failing write; the caller's close of f reports it too). */
int      sim_vcd_close(sim_vcd *v);
/* Stop watching and free v, writing nothing more (on bad-input errors,
 * when the caller discards the file). */
void     sim_vcd_abort(sim_vcd *v);
/* GTKWave save file for the dump at dump_path, written to f (the caller
 * opened gtkw_path as f, and closes it). It names the dump and itself by
 * absolute path ([dumpfile], [savefile]): GTKWave opens the dump from any
 * working directory, and finds it beside the save file when both were
 * moved together (it re-applies the dump's path relative to [savefile]).
 * A multi-bit signal with F = 1..30 fraction bits shows as fixed point
 * (GTKWave's "Fixed Point" decimal with a binary point, [fpshift_count] F;
 * its display shifts by at most 30), other ones as signed or unsigned
 * decimal raws. `lead`, if any, is a first group titled lead_title (a
 * signal, or a real variable "scope.name"); then one group per scope
 * that has signals. 0, or -1 with errno (a path that does not resolve). */
typedef struct sim_gtkw_trace {
    const sim_signal *sig;      /* a signal of the design, or NULL and: */
    const char       *real;     /* a real variable, "tb.expected_y" */
} sim_gtkw_trace;
int      sim_vcd_write_gtkw(FILE *f, sim_ctx *c, const char *dump_path, const char *gtkw_path,
                            const char *lead_title, const sim_gtkw_trace *lead, int nlead);
/* The largest fraction-bit count shown as fixed point. */
#define SIM_GTKW_MAX_FPSHIFT 30
#endif
