/* tb_widths.h - the widths a unit's default formats can be built at.
 *
 * unit_min_width gives the smallest width the format rule follows without
 * widening a signal; at the top a rule can ask for more than a primitive
 * takes (a divider's remainder register past 62 bits), and the build then
 * refuses. tb_width_max finds that top by building the unit. */
#ifndef TB_WIDTHS_H
#define TB_WIDTHS_H
#include "testbench/tb.h"

/* The largest width <= 64 at which u builds with its default formats and
 * cfg's parameters (cfg->width is ignored); the build's message for the
 * width above it in err (empty when 64 builds). 0 when no width from
 * unit_min_width up builds. */
int tb_width_max(const unit_desc *u, const unit_cfg *cfg, char *err, size_t errlen);
/* 1 when cfg->width is past the top of u's range, with what every verb
 * says then in msg ("unit U builds with its default formats at widths
 * A..B only (why)", after the verb's name for the width); else 0. */
int tb_width_refuse(const unit_desc *u, const unit_cfg *cfg, char *msg, size_t len);
#endif
