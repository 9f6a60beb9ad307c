/* tb_netlist_int.h - what the netlist writer and reader share (tb_netlist.h). */
#ifndef TB_NETLIST_INT_H
#define TB_NETLIST_INT_H
#include "testbench/tb_netlist.h"
#include <stdio.h>

/* What a line adds to its element's constructor (the writer's self-check
 * finds them): the depth of a logic element in AND2 levels
 * (sim_logic_depth), a constant multiplier as a shift-and-add network
 * (brdf_cmul). */
enum { NL_FIX_DEPTH = 1u, NL_FIX_CSD = 2u };

/* A character of a signal or scope name. */
static inline int nl_name_char(char ch)
{
    return (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '_';
}
/* x in the fewest digits that read back as x (%.15g to %.17g). */
const char *nl_real_str(double x, char *buf, size_t len);
/* s as "..." with \\, \" and \n escaped. */
void nl_put_quoted(FILE *f, const char *s);
/* tb_netlist_load on text in memory (len bytes), named path in messages. */
const unit_desc *nl_load_text(const char *text, size_t len, const char *path, unit_cfg *cfg, unit_fmts *fm,
                              char *err, size_t errlen);
#endif
