/* tb_check.c - the checks of a run's figures: one value against its
 * ideal and bound (exactly, with sim_dy), the list of signals that
 * overflowed, and the verdict. A leaf: tb_run (every item in memory) and
 * tb_run_stream (tb_stream.c) both call it, so neither calls the other's
 * file for them. */
#include "testbench/tb.h"
#include "testbench/tb_stream.h"
#include <math.h>
#include <stdio.h>
#include <string.h>

const char *tb_check_name(int check)
{
    static const char *const n[] = { "ok", "exceeded", "unchecked", "no bound" };
    return (unsigned)check < 4 ? n[check] : "?";
}

/* The exact check of one value: TB_CHECK_OK / EXCEEDED / UNCHECKED, and
 * |hw - ideal| (as a double, for the report). */
int tb_check_value(int64_t raw, sim_fmt f, const sim_dy *exact, const sim_dy *den, const sim_dy *hi,
                   double ideal_d, const sim_dy *bound, double *err)
{
    return tb_check_value_at(raw, f, sim_fmt_lsb(f), exact, den, hi, ideal_d, bound, sim_dy_to_double(bound), err);
}

int tb_check_quick(int64_t raw, sim_fmt f, double lsb, double id_d, double bound_d, double *err)
{
    /* Fast and still exact in its verdict: the raw is exact in a double;
     * to_double errs by at most 2^-49 |I| (8 words summed), the
     * subtraction by 2^-53 of the result. Decide only outside that margin
     * (and away from subnormals; NaN never). (raw lsb is sim_fx_to_real's
     * value: exact, a product by 2^-F.) */
    if (f.width > 53) return -1;
    double hd = (double)raw * lsb, bd = bound_d;
    double dd = fabs(hd - id_d), eps = 0x1p-47 * (fabs(hd) + fabs(id_d) + bd);
    if ((id_d == 0 || fabs(id_d) > 0x1p-900) && (bd == 0 || bd > 0x1p-900)) {
        if (dd + eps < bd) { *err = dd; return TB_CHECK_OK; }
        if (dd - eps > bd) { *err = dd; return TB_CHECK_EXCEEDED; }
    }
    return -1;
}

int tb_check_value_at(int64_t raw, sim_fmt f, double lsb, const sim_dy *exact, const sim_dy *den, const sim_dy *hi,
                      double ideal_d, const sim_dy *bound, double bound_d, double *err)
{
    sim_dy hw, id, d;
    if (exact && hi) {
        /* the ideal is somewhere in [exact, hi]: within the bound if both
         * ends are; over it if the nearer end is */
        sim_dy dl, dh;
        sim_dy_raw(&hw, raw, f);
        sim_dy_sub(&dl, &hw, exact);
        sim_dy_abs(&dl, &dl);
        sim_dy_sub(&dh, &hw, hi);
        sim_dy_abs(&dh, &dh);
        if (dl.ovf || dh.ovf) { *err = fabs(sim_fx_to_real(raw, f) - ideal_d); return TB_CHECK_UNCHECKED; }
        int far_hi = sim_dy_cmp(&dh, &dl) > 0;
        *err = sim_dy_to_double(far_hi ? &dh : &dl);
        if (sim_dy_cmp(far_hi ? &dh : &dl, bound) <= 0) return TB_CHECK_OK;
        int inside = sim_dy_cmp(&hw, exact) >= 0 && sim_dy_cmp(&hw, hi) <= 0;
        if (!inside && sim_dy_cmp(far_hi ? &dl : &dh, bound) > 0) return TB_CHECK_EXCEEDED;
        return TB_CHECK_UNCHECKED;
    }
    if (exact && den) {
        /* ideal = num/den, den > 0: |hw - num/den| <= B iff |hw den - num| <= B den */
        sim_dy bd;
        sim_dy_raw(&hw, raw, f);
        sim_dy_mul(&hw, &hw, den);
        sim_dy_sub(&d, &hw, exact);
        sim_dy_abs(&d, &d);
        sim_dy_mul(&bd, bound, den);
        *err = sim_dy_to_double(&d) / sim_dy_to_double(den);
        if (d.ovf || bd.ovf) { *err = fabs(sim_fx_to_real(raw, f) - ideal_d); return TB_CHECK_UNCHECKED; }
        return sim_dy_cmp(&d, &bd) <= 0 ? TB_CHECK_OK : TB_CHECK_EXCEEDED;
    }
    if (exact && f.width <= 53) {
        int c = tb_check_quick(raw, f, lsb, exact->ovf ? NAN : sim_dy_to_double(exact), bound_d, err);
        if (c >= 0) return c;
    }
    sim_dy_raw(&hw, raw, f);
    const sim_dy *idp = exact;
    if (!exact) { sim_dy_double(&id, ideal_d); idp = &id; }
    sim_dy_sub(&d, &hw, idp);
    sim_dy_abs(&d, &d);
    *err = sim_dy_to_double(&d);
    if (d.ovf) { *err = fabs(sim_fx_to_real(raw, f) - ideal_d); return TB_CHECK_UNCHECKED; }
    if (exact) return sim_dy_cmp(&d, bound) <= 0 ? TB_CHECK_OK : TB_CHECK_EXCEEDED;
    sim_dy delta, dlo, dhi;
    sim_dy_double(&delta, TB_DOUBLE_IDEAL_REL * fmax(1.0, fabs(ideal_d)));
    sim_dy_add(&dhi, &d, &delta);
    sim_dy_sub(&dlo, &d, &delta);
    if (sim_dy_cmp(&dhi, bound) <= 0) return TB_CHECK_OK;
    if (sim_dy_cmp(&dlo, bound) > 0) return TB_CHECK_EXCEEDED;
    return TB_CHECK_UNCHECKED;
}

void tb_overflow_list(const tb_result *r, char *buf, size_t len)
{
    size_t n = 0;
    if (len) buf[0] = 0;
    for (int i = 0; i < r->nsigs && n + 1 < len; i++)
        if (r->sigs[i].overflows) {
            int w = snprintf(buf + n, len - n, "%s%s:%llu", n ? " " : "", r->sigs[i].name,
                             (unsigned long long)r->sigs[i].overflows);
            if (w < 0 || (size_t)w >= len - n) { buf[n] = 0; break; }
            n += (size_t)w;
        }
}

void tb_verdict(tb_result *r, const tb_accept *a)
{
    tb_accept none;
    memset(&none, 0, sizeof none);
    if (!a) a = &none;
    r->target_set = a->max_error > 0 || a->max_nmse > 0 || a->max_lsb > 0;
    r->target_met = (!(a->max_error > 0) || r->max_abs_err <= a->max_error)
                 && (!(a->max_nmse > 0) || r->nmse <= a->max_nmse)
                 && (!(a->max_lsb > 0) || r->max_err_lsb <= a->max_lsb);
    r->ok = 0;
    char ov[120];
    tb_overflow_list(r, ov, sizeof ov);
    if (r->overflows && !a->allow_overflow)
        snprintf(r->why, sizeof r->why, "OVERFLOW on %.120s (--allow-overflow accepts it)", ov);
    else if (r->bound_check == TB_CHECK_EXCEEDED)
        snprintf(r->why, sizeof r->why, "EXCEEDED its derived bound, first at vector %zu", r->first_violation);
    else if (r->bound_check == TB_CHECK_NO_BOUND && !r->target_set)
        snprintf(r->why, sizeof r->why, "NO BOUND: the unit derives none for these formats, so the error is not checked "
                 "(a target, --max-error, --max-nmse or --max-lsb, decides instead)");
    else if (r->bound_check == TB_CHECK_UNCHECKED)
        snprintf(r->why, sizeof r->why, "UNCHECKED: the unit's ideal is a double that cannot decide the bound at vector %zu",
                 r->first_violation);
    else if (!r->golden_ok) {
        const tb_metrics *m = r->out;
        for (int o = 0; o < r->n_out; o++) if (!r->out[o].golden_ok) { m = &r->out[o]; break; }
        snprintf(r->why, sizeof r->why, "GOLDEN MISMATCH: %.15s at vector %zu is %.4g from the expected value, %.4g allowed",
                 m->name, m->golden_first, m->golden_err, m->golden_allowed);
    } else if (r->target_set && !r->target_met)
        snprintf(r->why, sizeof r->why, "MISSES YOUR TARGET (%s)",
                 r->bound_check == TB_CHECK_NO_BOUND ? "no bound derived" : "within the derived bound");
    else {
        /* without a derived bound (a datapath file with logic of its own,
         * a mix of rounding modes) the target alone decides */
        r->ok = 1;
        snprintf(r->why, sizeof r->why, "%s", r->bound_check == TB_CHECK_NO_BOUND ? "ok: meets your target (no bound derived)"
                                              : r->target_set ? "ok: within the derived bound and meets your target"
                                                              : "ok: within the derived bound (no target set)");
    }
}
