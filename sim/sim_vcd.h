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

/* Open and attach; timescale like "1ns". NULL with a message on failure. */
sim_vcd *sim_vcd_open(sim_ctx *c, const char *path, const char *timescale,
                      char *err, size_t errlen);
/* Kernel hook: time step t has finished; dump what changed. */
void     sim_vcd_step(sim_vcd *v, sim_time t);
/* Finish, flush and rename into place; 0 on success, -1 on an I/O error. */
int      sim_vcd_close(sim_vcd *v);
/* Remove the temporary file without publishing it (on bad-input errors). */
void     sim_vcd_abort(sim_vcd *v);
/* Write a GTKWave save file listing each scope's signals as a group. */
int      sim_vcd_write_gtkw(sim_ctx *c, const char *vcd_path, const char *gtkw_path);
#endif
