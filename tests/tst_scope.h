/* tst_scope.h - looking names up in a built design's scopes, for the tests
 * that check which signals a unit builds (test_sigset, test_conform). */
#ifndef TST_SCOPE_H
#define TST_SCOPE_H
#include "sim/sim.h"
#include <string.h>

/* Name appears as a signal or a sub-scope anywhere under sc. */
static int in_tree(const sim_scope *sc, const char *name)
{
    if (sc->name && !strcmp(sc->name, name)) return 1;
    for (const sim_signal *s = sc->first_sig; s; s = s->next_in_scope)
        if (!strcmp(s->name, name)) return 1;
    for (const sim_scope *k = sc->first_child; k; k = k->next_sibling)
        if (in_tree(k, name)) return 1;
    return 0;
}

/* Name is a signal of the top scope itself. */
static int at_top(const sim_scope *sc, const char *name)
{
    for (const sim_signal *s = sc->first_sig; s; s = s->next_in_scope)
        if (!strcmp(s->name, name)) return 1;
    return 0;
}
#endif
