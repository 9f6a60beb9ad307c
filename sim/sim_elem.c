/* sim_elem.c - sim_elem.h's columns as tables, for the engines that look
 * a kind up at run time rather than switch on it. */
#include "sim/sim.h"

#define ROW_NAME(K, name, ...) [SIM_KIND_##K] = name,
static const char *const kind_name[SIM_KIND__COUNT] = { SIM_ELEM_LIST(ROW_NAME) };
#define ROW_ROLE(K, name, role, ...) [SIM_KIND_##K] = role,
static const signed char kind_role[SIM_KIND__COUNT] = { SIM_ELEM_LIST(ROW_ROLE) };
#define ROW_EVAL(K, name, role, eval, ...) [SIM_KIND_##K] = SIM_KIND_##eval,
static const unsigned char kind_eval[SIM_KIND__COUNT] = { SIM_ELEM_LIST(ROW_EVAL) };
#define ROW_AREA(K, name, role, eval, vlog, energy, area, delay) [SIM_KIND_##K] = area,
static const unsigned char kind_area[SIM_KIND__COUNT] = { SIM_ELEM_LIST(ROW_AREA) };
#define ROW_DELAY(K, name, role, eval, vlog, energy, area, delay) [SIM_KIND_##K] = delay,
static const unsigned char kind_delay[SIM_KIND__COUNT] = { SIM_ELEM_LIST(ROW_DELAY) };

static int ok(sim_kind k) { return (unsigned)k < SIM_KIND__COUNT; }

const char *sim_kind_name(sim_kind k) { return ok(k) ? kind_name[k] : NULL; }
int sim_kind_role(sim_kind k) { return ok(k) ? kind_role[k] : -1; }
sim_kind sim_kind_eval(sim_kind k) { return ok(k) ? (sim_kind)kind_eval[k] : k; }
int sim_kind_has_area(sim_kind k) { return ok(k) && kind_area[k]; }
int sim_kind_has_delay(sim_kind k) { return ok(k) && kind_delay[k]; }
