/* test_area_tables.c - hf_lookup's texel reads in the area model: each of
 * a lookup's four reads is its own table of R x R words (the export's case
 * statement a read), costed at the GE a bit such a table maps to, against
 * the areas Yosys and ABC map the export's block to. */
#include "tests/tst.h"
#include "testbench/tb.h"
#include "units/unit.h"
#include <string.h>

/* The signal named name in scope path a.b (NULL: none). */
static const sim_signal *find(const sim_scope *sc, const char *scope, const char *name)
{
    const char *dot = strchr(scope, '.');
    size_t n = dot ? (size_t)(dot - scope) : strlen(scope);
    for (const sim_scope *ch = sc->first_child; ch; ch = ch->next_sibling)
        if (strlen(ch->name) == n && !strncmp(ch->name, scope, n)) {
            if (dot) return find(ch, dot + 1, name);
            for (const sim_signal *s = ch->first_sig; s; s = s->next_in_scope)
                if (!strcmp(s->name, name)) return s;
        }
    return NULL;
}

/* One read, l0's t00, at widths 8, 16, 24 (the default L = 8: 64 words of
 * W bits): the model charges 0.29 GE a bit, 64 W 0.29; mapped, the
 * export's block `l0_rom_t00` is 151.7, 289.7 and 434.7 GE (`sh
 * scripts/rom_area.sh L`, L the NanGate45 typical Liberty, Yosys 0.23,
 * ABC's light script), within 5% of it at each width. */
static void texel_read_as_mapped(void)
{
    static const struct { int w; double mapped; } m[] = { { 8, 151.7 }, { 16, 289.7 }, { 24, 434.7 } };
    const unit_desc *u = unit_find("hf_lookup");
    TST_CHECK(u != NULL, "no unit hf_lookup");
    if (!u) return;
    for (size_t i = 0; i < sizeof m / sizeof m[0]; i++) {
        unit_cfg cfg;
        unit_cfg_default(u, &cfg);
        cfg.width = m[i].w;
        unit_fmts f;
        tb_built b;
        char err[256];
        TST_CHECK(!tb_formats(u, &cfg, NULL, 0, &f, err, sizeof err), "%s", err);
        if (tb_build(u, &cfg, &f, &b, err, sizeof err)) { TST_CHECK(0, "%s", err); sim_free(b.c); continue; }
        const sim_signal *t = find(b.sc, "l0.rom", "t00");
        TST_CHECK(t != NULL, "no l0.rom.t00 at width %d", m[i].w);
        if (t) {
            int bits = t->fmt.width;
            TST_EQ_INT(bits, m[i].w);
            TST_NEAR(t->area_ge, cfg.L * cfg.L * bits * 0.29, 1e-9);
            double r = t->area_ge / m[i].mapped;
            TST_CHECK(r >= 0.95 && r <= 1.05, "width %d: model %.1f, mapped %.1f", m[i].w, t->area_ge, m[i].mapped);
        }
        sim_free(b.c);
    }
}

int main(void)
{
    TST_RUN(texel_read_as_mapped);
    TST_EXIT();
}
