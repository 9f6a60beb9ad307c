/* sim_deltas.h - the delta-cycle loop, evaluate then update, written once
 * and compiled twice by sim_sched.c (so no include guard: each include is
 * one copy). The evaluate phase dispatches on each process's operation
 * with vmdispatch / vmcase / vmbreak, as Lua's interpreter does (lvm.c,
 * ljumptab.h), which compile to
 *  - a computed goto (a GNU C extension gcc and clang both have): a table
 *    load and a jump, without the bounds check and the reload of op a
 *    switch costs, and each operation ends by starting the next process
 *    (the compiler may merge those tails);
 *  - or a plain switch in a loop: the reference copy's form, and the fast
 *    copy's too when built with -DSIM_KERNEL_SWITCH=1.
 * Before each include, sim_sched.c defines
 *   SIM__DELTAS_NAME    the function's name;
 *   SIM__DELTAS_REF     1: every primitive is evaluated by sim_elem_eval
 *                       from its record, any other process runs its
 *                       function (the reference: no operation inline, no
 *                       table, no shortcut), 0: the operation sim__proc.op
 *                       says;
 *   SIM__DELTAS_SWITCH  1: the switch, 0: the computed goto;
 * and the end of this file undefines them.
 *
 * The function: delta cycles while anything is runnable (one only, if
 * once). *deltas counts them within the time step; returns 1 when the
 * bound was reached with work left (a loop), else 0. With once,
 * c->changed is the number of signals the update changed, and they are
 * at the front of the update list (for the loop report). The run lists
 * stay in locals for the whole call (no process reads them: processes
 * only write signals, through c->q), and are handed back to the context
 * at the end. */

#if SIM__DELTAS_REF
#define SIM__DELTAS_OP(p) SIM__OP_FN
#else
#define SIM__DELTAS_OP(p) (p)->op
#endif
#if SIM__DELTAS_SWITCH
#define vmdispatch(o)   switch (o)
#define vmcase(op, l)   case op: l: __attribute__((unused));
#define vmbreak         break
#else
#define vmdispatch(o)   goto *op_label[o];
#define vmcase(op, l)   l:
/* Start process i + 1, or end the evaluate phase. */
#define vmbreak         do { if (++i < nrun) { p = run[i]; p->runs++; vmdispatch(SIM__DELTAS_OP(p)) } \
                             goto evaluated; } while (0)
#endif
/* y <= (x + radd) >> k (arithmetic: floor) when in range; out of range,
 * the general evaluation counts the overflow. */
#define QUANT(x) do { v = SIM_OP_QUANT(x, p->op_radd, p->op_k);                        \
                      if (__builtin_expect(v < p->op_lo || v > p->op_hi, 0)) goto general; } while (0)
/* The same when radd and k are 0 (the *_X operations). */
#define RANGE(x) do { v = (int64_t)(x); \
                      if (__builtin_expect(v < p->op_lo || v > p->op_hi, 0)) goto general; } while (0)
/* y <= v: queued unless it is y's value and nothing else is pending (as
 * sim_write). */
#define WRITE_Y() do { sim_signal *y = p->op_y; y->nxt = v; \
                       if (!y->queued && v != y->cur) { y->queued = 1; upd[nupd++] = y; } } while (0)

static int SIM__DELTAS_NAME(sim_ctx *c, uint32_t *deltas, int once)
{
#if !SIM__DELTAS_SWITCH
    /* The table is made from SIM__OP_LIST (sim_internal.h). */
#define OP_LABEL(O, label, x) [SIM__OP_##O] = &&label,
    static const void *const op_label[] = { SIM__OP_LIST(OP_LABEL) };
#undef OP_LABEL
    _Static_assert(sizeof op_label / sizeof *op_label == SIM__OP__COUNT, "one label per SIM__OP_*");
#endif
    sim__proc **run = c->run, **next = c->run2;
    uint32_t nrun = c->nrun;
    uint64_t gen = c->gen;
    sim_signal **upd = c->q.upd;
    uint32_t nd = *deltas;
    int hit = 0;
#if !SIM__DELTAS_REF
    c->stats.fast_paths++;
#endif
    for (;;) {
        uint32_t nupd = c->q.nupd, i;
        sim__proc *p;
        int64_t v;
        for (i = 0; i < nrun; i++) {
            /* Count the run, go to its operation. (It may be woken again
             * for the next delta: that list has the next generation,
             * which no process is listed under yet.) */
            p = run[i];
            p->runs++;
            vmdispatch(SIM__DELTAS_OP(p)) {
            vmcase(SIM__OP_FN, general)
                /* Anything the kernel does not know inline, and a
                 * primitive whose fast result is out of range. */
                c->q.nupd = nupd;
#if SIM__DELTAS_REF
                /* a primitive: its one definition, from its record */
                if (p->elem) sim__elem_step(p);
                else p->fn(&p->pub);
#else
                p->fn(&p->pub);
#endif
                nupd = c->q.nupd;
                vmbreak;
            /* Operands' widths bound the exact result below 2^62
             * (sim_prim.c checks, sim_op.h's conditions); the operations
             * are sim_op.h's in uint64_t, so that even a raw forced
             * outside its format cannot overflow. */
            vmcase(SIM__OP_COPY, op_copy)   QUANT(p->op_a->cur); WRITE_Y(); vmbreak;
            vmcase(SIM__OP_ADD, op_add)     QUANT(SIM_OP_ADD(uint64_t, p->op_a->cur, p->op_b->cur)); WRITE_Y(); vmbreak;
            vmcase(SIM__OP_SUB, op_sub)     QUANT(SIM_OP_SUB(uint64_t, p->op_a->cur, p->op_b->cur)); WRITE_Y(); vmbreak;
            vmcase(SIM__OP_MUL, op_mul)     QUANT(SIM_OP_MUL(uint64_t, p->op_a->cur, p->op_b->cur)); WRITE_Y(); vmbreak;
            vmcase(SIM__OP_MUX, op_mux) {
                    uint64_t sel = (uint64_t)p->op_c->cur;
                    if (!SIM_OP_SEL_IN(sel, p->op_n)) { v = 0; WRITE_Y(); vmbreak; }
                    QUANT(p->op_in[sel]->cur); WRITE_Y(); vmbreak;
                }
            vmcase(SIM__OP_BK, op_bk)
                if (!p->op_c->cur) { v = 0; WRITE_Y(); vmbreak; }
                QUANT(p->op_a->cur); WRITE_Y(); vmbreak;
            vmcase(SIM__OP_COPY_X, op_copy_x) RANGE(p->op_a->cur); WRITE_Y(); vmbreak;
            vmcase(SIM__OP_ADD_X, op_add_x)   RANGE(SIM_OP_ADD(uint64_t, p->op_a->cur, p->op_b->cur)); WRITE_Y(); vmbreak;
            vmcase(SIM__OP_SUB_X, op_sub_x)   RANGE(SIM_OP_SUB(uint64_t, p->op_a->cur, p->op_b->cur)); WRITE_Y(); vmbreak;
            vmcase(SIM__OP_MUX_X, op_mux_x) {
                    uint64_t sel = (uint64_t)p->op_c->cur;
                    if (!SIM_OP_SEL_IN(sel, p->op_n)) { v = 0; WRITE_Y(); vmbreak; }
                    RANGE(p->op_in[sel]->cur); WRITE_Y(); vmbreak;
                }
            vmcase(SIM__OP_BK_X, op_bk_x)
                if (!p->op_c->cur) { v = 0; WRITE_Y(); vmbreak; }
                RANGE(p->op_a->cur); WRITE_Y(); vmbreak;
            vmcase(SIM__OP_LOGIC_S, op_logic_s)
                v = (int64_t)((uint64_t)logic_call(p) << p->op_k) >> p->op_k;
                WRITE_Y(); vmbreak;
            vmcase(SIM__OP_LOGIC_U, op_logic_u)
                v = (int64_t)((uint64_t)logic_call(p) & (uint64_t)p->op_radd);
                WRITE_Y(); vmbreak;
            vmcase(SIM__OP_LUT1, op_lut1) {
                    uint64_t ix = (uint64_t)p->op_a->cur - (uint64_t)p->op_lo;
                    if (__builtin_expect(ix > (uint64_t)p->op_hi, 0)) goto general;
                    v = p->op_tab[ix];
                    WRITE_Y(); vmbreak;
                }
            vmcase(SIM__OP_LUTN, op_lutn) {
                    uint64_t ix = 0;
                    for (uint32_t j = 0; j < p->op_n; j++) {
                        const sim__lut_in *t = &p->op_tin[j];
                        uint64_t d = (uint64_t)p->op_in[j]->cur - (uint64_t)t->lo;
                        if (__builtin_expect(d > t->span, 0)) goto general;
                        ix |= d << t->sh;
                    }
                    v = p->op_tab[ix];
                    WRITE_Y(); vmbreak;
                }
            }
        }
    evaluated: __attribute__((unused));   /* the goto form jumps here */
        c->stats.proc_runs += nrun;
        nd++;
        uint32_t nnext = 0, changed;
        gen++;
        if (__builtin_expect(once, 0)) changed = update(c, upd, nupd, next, &nnext, gen, c->chg_on != NULL, 1);
        else if (c->chg_on) changed = update(c, upd, nupd, next, &nnext, gen, 1, 0);
        else changed = update(c, upd, nupd, next, &nnext, gen, 0, 0);
        sim__proc **t = run; run = next; next = t;
        nrun = nnext;
        /* Counted after the update (nothing runs in between, so nobody
         * sees the difference): next to proc_runs's, gcc pairs the two
         * additions in a vector register, which costs more. */
        c->stats.deltas++;
        if (once) { c->changed = changed; break; }
        /* The update leaves no write pending, so what is left is the
         * processes it woke. */
        if (!nrun) break;
        if (nd >= c->max_deltas) { hit = 1; break; }
    }
    c->run = run; c->nrun = nrun;
    c->run2 = next;
    c->gen = gen;
    *deltas = nd;
    return hit;
}

#undef vmdispatch
#undef vmcase
#undef vmbreak
#undef QUANT
#undef RANGE
#undef WRITE_Y
#undef SIM__DELTAS_OP
#undef SIM__DELTAS_NAME
#undef SIM__DELTAS_REF
#undef SIM__DELTAS_SWITCH
