/* sim_area_net.h - the area terms of a design that no element knows when
 * it is built, since they depend on what reads it: the buffer trees of
 * its heavy nets, and the incrementers a multi-operand adder shares. */
#ifndef SIM_AREA_NET_H
#define SIM_AREA_NET_H
#include "sim/sim.h"

/* GE to add to the elements' own areas over scope sc and its children:
 * each bit of a signal of more load than an X1 cell drives at its
 * figures gets the buffers of a tree of fanout four
 * (sim_area_buffers); an adder whose one reader is another adder (the
 * two one multi-operand adder, as the delay model takes them:
 * sim_delay_csa) gives back its incrementer over the bits above its
 * chain, which the last adder's covers (negative). 0 on no memory. */
double sim_area_net(const sim_scope *sc);
#endif
