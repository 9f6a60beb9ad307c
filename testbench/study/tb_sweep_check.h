/* tb_sweep_check.h - what the sweep's target search is checked with,
 * once it has chosen a design per settings group (tb_sweep_target): the
 * held-out stimuli, and under --ranges derived the chosen design's derived
 * intervals beside its observed ones. The verb sweep prints and writes them
 * (testbench/cli/cli_sweep_target.c, cli_sweep_ranges.c). */
#ifndef TB_SWEEP_CHECK_H
#define TB_SWEEP_CHECK_H
#include "testbench/study/tb_sweep.h"

/* Every group's search result res[g] (those that met the target) run on
 * held-out stimuli: vectors of `seed` made by the unit's reference, as
 * many as the sweep used, once per parameter set (the generators put their
 * full-range corner values first whatever the seed); tb_sweep_target_heldout
 * fills res[g].heldout*. *failed: 1 when some group's check failed. 0, or
 * -1 with a message when the stimuli or a run could not be made. */
int tb_sweep_heldout_all(const tb_sweep *s, tb_target_res *res, tb_target_kind k, double target, uint64_t seed,
                         int *failed, char *err, size_t errlen);

/* Each met group's chosen design (res[g].fmts at its uniform row's
 * configuration) derived over rg into dres[g], and run on the sweep's
 * vectors for its observed ranges into dobs[g] (both [ngroups], zeroed by
 * the caller). TB_OK; TB_BADINPUT (no derivation) or the run's status,
 * with a message. */
int tb_sweep_derived_all(const tb_sweep *s, const tb_target_res *res, const tb_ranges *rg, tb_derived *dres,
                         tb_result *dobs, char *err, size_t errlen);
#endif
