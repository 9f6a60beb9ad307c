/* test_netlist.c - the netlist text (testbench/tb_netlist.h) in process:
 * every unit and schedule written, read back and run on the kernel gives
 * the unit's own JSON report byte for byte (counters included); the text
 * is the same bytes twice; malformed texts are refused with their
 * FILE:LINE message and build nothing. tests/cli_netlist.sh does the same
 * through the command line (and the VCD); this one is cheap enough for the
 * sanitizer build. */
#include "tests/tst.h"
#include "testbench/tb_netlist.h"
#include <stdlib.h>
#include <string.h>

/* The text of unit u at cfg (malloc'd), or NULL. */
static char *text_of(const unit_desc *u, const unit_cfg *cfg, char *err, size_t errlen)
{
    char *buf = NULL;
    size_t len;
    FILE *m = open_memstream(&buf, &len);
    if (!m) return NULL;
    int rc = tb_netlist_write(m, u, cfg, NULL, 0, err, errlen);
    fclose(m);
    if (rc) { free(buf); return NULL; }
    return buf;
}

static char tmp_dir[] = "/tmp/test_netlist.XXXXXX";

/* text into a file of the scratch folder; its path in path. */
static void put_file(const char *text, const char *name, char *path, size_t len)
{
    snprintf(path, len, "%s/%s", tmp_dir, name);
    FILE *f = fopen(path, "w");
    if (!f) return;
    fputs(text, f);
    fclose(f);
}

/* The JSON report of a kernel run of u (malloc'd). */
static char *json_of(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fm, const vec_set *vs)
{
    tb_result r;
    char err[600], *buf = NULL;
    size_t len;
    tb_opts o = { 0 };
    if (tb_run(u, cfg, fm, vs, &o, &r, err, sizeof err) != TB_OK) {
        printf("  run %s: %s\n", u->name, err);
        return NULL;
    }
    tb_verdict(&r, NULL);
    FILE *m = open_memstream(&buf, &len);
    if (m) { tb_write_json(m, &r); fclose(m); }
    tb_result_free(&r);
    return buf;
}

static void test_round_trip_every_unit(void)
{
    int designs = 0;
    for (size_t i = 0; i < unit_count(); i++) {
        const unit_desc *u = unit_at(i);
        for (int s = 0; s < u->nsched; s++) {
            unit_cfg cfg;
            unit_cfg_default(u, &cfg);
            cfg.schedule = s;
            char err[600], path[300];
            char *t = text_of(u, &cfg, err, sizeof err);
            TST_CHECK(t, "%s %s: %s", u->name, u->sched[s].name, err);
            if (!t) continue;
            char *t2 = text_of(u, &cfg, err, sizeof err);
            TST_CHECK(t2 && !strcmp(t, t2), "%s %s: the text differs between two writes", u->name, u->sched[s].name);
            free(t2);
            put_file(t, "n.net", path, sizeof path);
            free(t);
            unit_cfg ncfg;
            unit_fmts nfm, fm;
            const unit_desc *nu = tb_netlist_load(path, &ncfg, &nfm, err, sizeof err);
            TST_CHECK(nu, "%s %s: %s", u->name, u->sched[s].name, err);
            if (!nu) continue;
            TST_CHECK(tb_netlist_is(nu) && !tb_netlist_is(u), "%s: which unit is a netlist's", u->name);
            TST_CHECK(!memcmp(&ncfg, &cfg, sizeof cfg), "%s %s: the configuration read back differs", u->name,
                      u->sched[s].name);
            tb_formats(u, &cfg, NULL, 0, &fm, err, sizeof err);
            for (int k = 0; k < u->nsigs; k++)
                TST_CHECK(!unit_sig_built(u, k, &cfg) || !memcmp(&nfm.f[k], &fm.f[k], sizeof fm.f[k]),
                          "%s %s: the format of %s read back differs", u->name, u->sched[s].name, u->sigs[k].name);
            vec_set vs;
            if (tb_make_vectors(u, &cfg, 24, 5, &vs, err, sizeof err)) {
                TST_CHECK(0, "%s: vectors: %s", u->name, err);
                tb_netlist_free(nu);
                continue;
            }
            char *a = json_of(u, &cfg, &fm, &vs), *b = json_of(nu, &ncfg, &nfm, &vs);
            TST_CHECK(a && b && !strcmp(a, b), "%s %s: run from the text differs from the unit's", u->name,
                      u->sched[s].name);
            TST_CHECK(a && strstr(a, "\"engine\": \"kernel\""), "%s: the kernel's counters are in the report", u->name);
            free(a);
            free(b);
            vec_set_free(&vs);
            tb_netlist_free(nu);
            designs++;
        }
    }
    TST_CHECK(designs >= 40, "%d designs", designs);
}

/* Malformed texts: horner3's text with one edit (the first occurrence of
 * from replaced by to), refused with "PATH:LINE: want..." where LINE is
 * the edit's line (0: "PATH: want", no line). */
static void test_malformed(void)
{
    static const struct { const char *from, *to, *want; int line_of_edit; } cases[] = {
        { "add sm s7.9 a=mx2", "add sm s7.9 a=mx9", "add sm: a=mx9 is not declared", 1 },
        { "bk bk ", "bk mx1 ", "mx1: declared twice (first at line", 1 },
        { "in=a,rg", "in=a,sm", "mux mx1: in=sm is made at line", 1 },
        { "add sm s7.9", "add sm s7.x", "format s7.x", 1 },
        { "add sm", "adder sm", "adder: not a line of a netlist", 1 },
        { "a=mx2 b=bk", "a=mx2 b=bk sel=rg", "sel=: not an attribute of add", 1 },
        { "a=mx2 b=bk", "a=mx2", "add sm: needs b=NAME", 1 },
        { "table=10111100", "table=1011110", "logic mx1_sel: table= has 7 hex digits, its 8 rows of 1 need 8", 1 },
        { "table=10111100", "table=1011110G", "logic mx1_sel: table=: 'G' is not a lower-case hex digit", 1 },
        { "table=10111100", "table=1011110f", "logic mx1_sel: table= row 7: f has more bits than mx1_sel's 1", 1 },
        { "unit horner3\n", "unit horner9\n", "unit horner9: no such built-in unit", 1 },
        { "netlist 1", "netlist 2", "netlist 2: this reader knows version 1", 1 },
        { "add sm ", "add dp.sm ", "dp.sm: scope dp is not declared", 1 },
        { "port out y\n", "", ": 5 input and 0 output ports; unit horner3 has 5 and 1", 0 },
        { "port in a\n", "port in sm\n", "port in sm: not an input without from=", 1 },
        { "pass=bk_pass", "pass=clk", "bk bk: pass=clk is the clock", 1 },
        { "d=sm clk=clk", "d=sm clk=step", "reg rg: clk=step is not the clock", 1 },
        { "shift y s7.9 x=rg by=0", "shift y s7.9 x=rg by=65", "by=65: expected a whole number -64..64", 1 },
        { "a=mx2 b=bk", "a=mx2 b=bk a=rg", "a= given twice", 1 },
        { "logic mx1_sel u1.0 in=step ", "logic mx1_sel u1.0 in=step,a ", "logic mx1_sel: inputs of 19 bits in all", 1 },
        { "area=12 table=10111100", "area=12 fn=unit fn=unit", "fn= given twice", 1 },
        { "reg rg s7.9", "logic zz u1.0 in=step area=1 fn=unit\nreg rg s7.9", "logic zz: fn=unit, but unit horner3 has no logic element zz", 1 },
        { "area=12 table=10111100", "table=10111100", "logic mx1_sel: needs area=GE", 1 },
        { "clock clk\n", "", ": no clock NAME line", 0 },
        { "input t u1.15", "input t u1.15 from=\"t", "a quoted text without its closing", 1 },
        { "input t u1.15", "input t u1.15 from=\"t\\q\"", "'\\q' in a quoted text", 1 },
        { "input t u1.15", "input t u1.15 from=t", "input t: from=t names itself", 1 },
        { "mul mul s7.9 a=mx1 b=t", "mul mul s7.9 a=mx1 b=t net=csd", "mul mul: net=csd needs a constant b=", 1 },
        { "reg rg s7.9", "logic zz u2.0 in=step area=0 bits={%0[5],1'b1}\nreg rg s7.9",
          "logic zz: bits={%0[5],1'b1}: expected", 1 },
        { "reg rg s7.9", "logic zz u2.0 in=step area=0 bits={%0[2],2'b100}\nreg rg s7.9",
          "logic zz: bits={%0[2],2'b100}: expected", 1 },
        { "area=12 table=10111100", "area=12 bits=%0[0] table=10111100",
          "logic mx1_sel: needs one of table=HEX, bits=WIRING, fn=verilog and fn=unit", 1 },
    };
    unit_cfg cfg;
    const unit_desc *u = unit_find("horner3");
    unit_cfg_default(u, &cfg);
    char err[600], path[300];
    char *base = text_of(u, &cfg, err, sizeof err);
    TST_CHECK(base, "%s", err);
    if (!base) return;
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        const char *at = strstr(base, cases[k].from);
        TST_CHECK(at, "case %zu: '%s' is not in the text", k, cases[k].from);
        if (!at) continue;
        size_t pre = (size_t)(at - base), lf = strlen(cases[k].from), lt = strlen(cases[k].to);
        char *t = malloc(strlen(base) - lf + lt + 1);
        memcpy(t, base, pre);
        memcpy(t + pre, cases[k].to, lt);
        strcpy(t + pre + lt, at + lf);
        int line = 1;
        for (size_t i = 0; i < pre; i++) line += base[i] == '\n';
        put_file(t, "bad.net", path, sizeof path);
        free(t);
        char want[700];
        if (cases[k].line_of_edit) snprintf(want, sizeof want, "%s:%d: %s", path, line, cases[k].want);
        else snprintf(want, sizeof want, "%s%s", path, cases[k].want);
        unit_cfg c2;
        unit_fmts f2;
        err[0] = 0;
        const unit_desc *nu = tb_netlist_load(path, &c2, &f2, err, sizeof err);
        TST_CHECK(!nu, "case %zu (%s): accepted", k, cases[k].want);
        if (nu) tb_netlist_free(nu);
        TST_CHECK(!strncmp(err, want, strlen(want)) && !strchr(err, '\n'), "case %zu: '%s', expected '%s...'", k, err,
                  want);
    }
    free(base);
}

int main(void)
{
    if (!mkdtemp(tmp_dir)) { printf("FAIL test_netlist: no scratch folder\n"); return 1; }
    TST_RUN(test_round_trip_every_unit);
    TST_RUN(test_malformed);
    tst_rmtree(tmp_dir);
    rmdir(tmp_dir);
    TST_EXIT();
}
