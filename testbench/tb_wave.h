/* tb_wave.h - what tb_run adds to a unit's value change dump: the
 * expected value and the error of every output beat (real variables
 * tb.expected_NAME and tb.err_NAME), a window of items, the GTKWave save
 * file, and the conversion to FST.
 *
 * The window --vcd-from N --vcd-to M (item indices from 0, as in --out's
 * index column) starts at the rising edge where the testbench first offers
 * item N (time 0 for N = 0: $dumpvars with every value, as a whole dump)
 * and ends with the rising edge that samples item M's last output beat
 * (the whole dump's last step when M is the last item).
 */
#ifndef TB_WAVE_H
#define TB_WAVE_H
#include "testbench/tb.h"
#include "sim/sim_vcd.h"
#include "base/base_out.h"

typedef struct tb_wave {
    const tb_opts   *o;
    const unit_io   *io;
    const sim_signal *clk;
    const vec_set   *vs;
    int       n_in, n_out, beats;
    size_t    n_items;
    size_t    from, to;           /* the window, items (to inclusive) */
    /* what the hook has seen, cycle by cycle */
    size_t    offered;            /* item offered in the current cycle */
    int       accepting;          /* the current cycle hands an item over */
    size_t    beats_seen;         /* output beats so far */
    long long prev_beat;          /* the beat valid in the previous cycle, or -1 */
    int       started;            /* the window has begun */
    int       real_idx[2 * UNIT_MAX_IO];
    char     *dump_path;          /* where sim_vcd writes (a temporary for --fst) */
    base_out  *out;                /* dump_path, open while the dump is written */
} tb_wave;

/* Open the dump for tb_run (o->vcd_path, or a temporary beside it with
 * o->fst), declare the real variables and the window. NULL with a message. */
sim_vcd *tb_wave_open(tb_wave *w, sim_ctx *c, const tb_opts *o, const unit_io *io,
                      const sim_signal *clk, const unit_desc *u, const unit_cfg *cfg,
                      const vec_set *vs, char *err, size_t errlen);
/* Close the dump (rc: tb_run's status so far), convert it to FST (o->fst),
 * write FILE.gtkw (o->gtkw, a dump in a regular file); returns the new
 * status (TB_BADINPUT with a message when a file cannot be written). */
int      tb_wave_close(tb_wave *w, sim_ctx *c, sim_vcd *v, const unit_desc *u, int rc,
                       char *err, size_t errlen);
/* Write VCD_PATH.gtkw, a GTKWave save file opening the dump with the
 * traces lead[0..nlead-1] first (sim_vcd.h), when vcd_path is a regular
 * file (not stdout or a device); 0, or -1 with a message. */
int      tb_wave_gtkw(sim_ctx *c, const char *vcd_path, const char *title, const sim_gtkw_trace *lead,
                      int nlead, char *err, size_t errlen);
/* Free what open allocated after a failure before the run, removing the
 * unfinished dump (the caller aborts the sim_vcd first). */
void     tb_wave_free(tb_wave *w);
/* 1 if vcd2fst is on PATH. */
int      tb_wave_have_vcd2fst(void);
#endif
