/* sim_vcd.h - IEEE 1364-2005 section 18 value change dump.
 *
 * The writer dumps every signal of the design (clock included) as a
 * `$var wire` of its width inside one `$scope module` per sim_scope, then
 * `$dumpvars` with the initial values and, at each time step, only the
 * signals whose value differs from what was last dumped.
 *
 * The file is written under a temporary name and renamed when closed, so a
 * path never holds a half-written dump; sim_vcd_close is also what to call
 * after a simulation error: the dump up to the error is kept, complete.
 */
#ifndef SIM_VCD_H
#define SIM_VCD_H
#include "sim/sim.h"

/* Open and attach; timescale like "1ns". NULL with a message on failure.
 * The header is written with the first time step (or at close), so that
 * real variables can be declared between open and the run. */
sim_vcd *sim_vcd_open(sim_ctx *c, const char *path, const char *timescale,
                      char *err, size_t errlen);
/* Kernel hook: time step t has finished; dump what changed. */
void     sim_vcd_step(sim_vcd *v, sim_time t);

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
/* Finish, flush and rename into place; 0 on success, -1 on an I/O error. */
int      sim_vcd_close(sim_vcd *v);
/* Remove the temporary file without publishing it (on bad-input errors). */
void     sim_vcd_abort(sim_vcd *v);
/* GTKWave save file (FILE.gtkw). It names the dump and itself by absolute
 * path ([dumpfile], [savefile]): GTKWave opens the dump from any working
 * directory, and finds it beside the save file when both were moved
 * together (it re-applies the dump's path relative to [savefile]). A
 * multi-bit signal with F = 1..30 fraction bits shows as fixed point
 * (GTKWave's "Fixed Point" decimal with a binary point, [fpshift_count] F;
 * its display shifts by at most 30), other ones as signed or unsigned
 * decimal raws. `lead`, if any, is a first group titled lead_title (a
 * signal, or a real variable "scope.name"); then one group per scope
 * that has signals. 0, or -1 with errno. */
typedef struct sim_gtkw_trace {
    const sim_signal *sig;      /* a signal of the design, or NULL and: */
    const char       *real;     /* a real variable, "tb.expected_y" */
} sim_gtkw_trace;
int      sim_vcd_write_gtkw(sim_ctx *c, const char *dump_path, const char *gtkw_path,
                            const char *lead_title, const sim_gtkw_trace *lead, int nlead);
/* The largest fraction-bit count shown as fixed point. */
#define SIM_GTKW_MAX_FPSHIFT 30
#endif
