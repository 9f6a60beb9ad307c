/* tb_synth.c - the export through Yosys and OpenSTA on a Liberty, or
 * Yosys and nextpnr on an iCE40 (tb_synth.h). The tools write their logs
 * and reports into dir; this file reads back the figures they print. */
#define _XOPEN_SOURCE 700          /* realpath, symlink */
#include "testbench/tb_synth.h"
#include "testbench/tb_verilog.h"
#include "base/base_out.h"
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* 1 if an executable `tool` is on PATH. */
static int on_path(const char *tool)
{
    const char *path = getenv("PATH");
    char buf[PATH_MAX];
    while (path && *path) {
        size_t n = strcspn(path, ":");
        snprintf(buf, sizeof buf, "%.*s/%s", (int)(n ? n : 1), n ? path : ".", tool);
        if (access(buf, X_OK) == 0) return 1;
        path += n + (path[n] == ':');
    }
    return 0;
}

static int need_tool(const char *tool, const char *pkg, char *err, size_t errlen)
{
    if (on_path(tool)) return 0;
    snprintf(err, errlen, "synth: %s not found (install the Debian package %s)", tool, pkg);
    return -1;
}

/* The last "N. Executing X pass" of a Yosys log still being written: the
 * pass now running, for the progress line (its last 8 KB are enough). */
static void yosys_pass(void *ctx, char *buf, size_t len)
{
    char path[PATH_MAX], line[400];
    snprintf(path, sizeof path, "%s/yosys.log", (const char *)ctx);
    FILE *f = fopen(path, "r");
    if (!f) return;
    if (fseek(f, -8192, SEEK_END) != 0) rewind(f);
    while (fgets(line, sizeof line, f)) {
        const char *x = strstr(line, ". Executing ");
        if (!x) continue;
        x += strlen(". Executing ");
        size_t n = strcspn(x, " \n");
        snprintf(buf, len, "%.*s", (int)n, x);
    }
    fclose(f);
}

int tb_synth_tool(tb_synth_run *run, const char *step, const char *dir, const char *cmd, int yosys,
                    char *err, size_t errlen)
{
    base_proc p = { "synth", step, dir, yosys ? yosys_pass : NULL, (void *)dir, run->start, run->limit_s,
                    run->progress, 0, 0 };
    /* The tools' own temporaries (Yosys's yosys-abc-XXXXXX folder for each
     * ABC call) go into the flow's folder, not $TMPDIR: a tool stopped by
     * the time limit or a signal leaves them behind, and the folder's
     * removal takes them with it. */
    char full[2048];
    int n = snprintf(full, sizeof full, "TMPDIR=\"$PWD\"; export TMPDIR; %s", cmd);
    if (n < 0 || (size_t)n >= sizeof full) { snprintf(err, errlen, "synth: %s: command too long", step); return TB_SYNTH_FAILED; }
    int rc = base_proc_run(full, &p, err, errlen);
    if (rc == BASE_PROC_ERROR) return TB_SYNTH_FAILED;
    if (rc == BASE_PROC_SIGNAL) { run->signal = p.signal; snprintf(err, errlen, "synth: interrupted"); return TB_SYNTH_SIGNAL; }
    if (rc == BASE_PROC_TIMEOUT) {
        snprintf(err, errlen, "synth: %s still running after the time limit of %.0f s (--timeout SECONDS)", step, run->limit_s);
        return TB_SYNTH_TIMEOUT;
    }
    return p.status == 0 ? TB_SYNTH_OK : TB_SYNTH_FAILED;
}

int tb_abc_auto(double model_ge) { return model_ge > TB_ABC_LIGHT_GE ? TB_ABC_LIGHT : TB_ABC_FULL; }

/* The first line of dir/log saying ERROR (else "see LOG"), as the failure's message. */
static int tool_failed(const char *dir, const char *log, const char *step, char *err, size_t errlen)
{
    char path[PATH_MAX], line[400];
    snprintf(path, sizeof path, "%s/%s", dir, log);
    FILE *f = fopen(path, "r");
    snprintf(err, errlen, "synth: %s failed (see %s: use --keep DIR)", step, log);
    while (f && fgets(line, sizeof line, f)) {
        if (!strstr(line, "ERROR") && !strstr(line, "Error")) continue;
        line[strcspn(line, "\n")] = 0;
        snprintf(err, errlen, "synth: %s failed: %s", step, line);
        break;
    }
    if (f) fclose(f);
    return TB_SYNTH_FAILED;
}

/* The export, the tools checked first. */
static int export_unit(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fm, const char *dir,
                       char *err, size_t errlen)
{
    if (need_tool("yosys", "yosys", err, errlen)) return TB_SYNTH_BADINPUT;
    if (tb_verilog_export(u, cfg, fm, dir, err, errlen)) return TB_SYNTH_BADINPUT;
    return TB_SYNTH_OK;
}

/* ------------------------------------------------------------ Liberty, STA */

/* dir/liberty.lib: the user's file unpacked (gzip's magic bytes) or
 * linked by its absolute path. */
static int liberty_in(const char *lib, const char *dir, tb_synth_run *run, char *err, size_t errlen)
{
    struct stat st;
    if (stat(lib, &st) == 0 && !S_ISREG(st.st_mode)) {
        snprintf(err, errlen, "synth: --liberty %s: not a file", lib);
        return TB_SYNTH_BADINPUT;
    }
    FILE *f = fopen(lib, "rb");
    if (!f) { snprintf(err, errlen, "synth: --liberty %s: %s", lib, strerror(errno)); return TB_SYNTH_BADINPUT; }
    unsigned char m[2] = { 0, 0 };
    size_t got = fread(m, 1, 2, f);
    fclose(f);
    char *abs = realpath(lib, NULL), src[PATH_MAX], dst[PATH_MAX];
    if (!abs) { snprintf(err, errlen, "synth: --liberty %s: %s", lib, strerror(errno)); return TB_SYNTH_BADINPUT; }
    int gz = got == 2 && m[0] == 0x1f && m[1] == 0x8b;
    snprintf(src, sizeof src, "%s/liberty.src", dir);
    snprintf(dst, sizeof dst, "%s/liberty.lib", dir);
    unlink(src);
    unlink(dst);
    int bad = symlink(abs, gz ? src : dst);
    free(abs);
    if (bad) { snprintf(err, errlen, "synth: cannot link the Liberty file into %s: %s", dir, strerror(errno)); return TB_SYNTH_BADINPUT; }
    if (!gz) return TB_SYNTH_OK;
    if (need_tool("gzip", "gzip", err, errlen)) return TB_SYNTH_BADINPUT;
    int rc = tb_synth_tool(run, "gzip", dir, "gzip -dc liberty.src >liberty.lib 2>gzip.log", 0, err, errlen);
    if (rc == TB_SYNTH_FAILED) snprintf(err, errlen, "synth: --liberty %s: gzip cannot unpack it", lib);
    return rc;
}

/* The smallest cell of the library whose name holds `part` (any case),
 * `want` itself when the library has it (cell (NAME) { ... area : A;
 * ...): its area into *area and its name into name, 0 if none. */
static void lib_cell(const char *dir, const char *part, const char *want, char *name, size_t len, double *area)
{
    char path[PATH_MAX], line[512], cell[64] = "", low[64];
    snprintf(path, sizeof path, "%s/liberty.lib", dir);
    FILE *f = fopen(path, "r");
    *area = 0;
    name[0] = 0;
    while (f && fgets(line, sizeof line, f)) {
        const char *c = strstr(line, "cell (");
        if (c && (c == line || c[-1] == ' ' || c[-1] == '\t')) {
            if (sscanf(c, "cell ( \"%63[^\"]", cell) != 1 && sscanf(c, "cell (%63[^) ]", cell) != 1) cell[0] = 0;
            continue;
        }
        const char *a = strstr(line, "area");
        double v;
        if (!cell[0] || !a || sscanf(a, "area : %lf", &v) != 1) continue;
        size_t i;
        for (i = 0; cell[i] && i + 1 < sizeof low; i++) low[i] = (char)(cell[i] >= 'A' && cell[i] <= 'Z' ? cell[i] - 'A' + 'a' : cell[i]);
        low[i] = 0;
        int is_want = !strcmp(cell, want), have_want = !strcmp(name, want);
        if (strstr(low, part) && v > 0 && !have_want && (is_want || !*area || v < *area)) {
            *area = v;
            snprintf(name, len, "%s", cell);
        }
        cell[0] = 0;            /* the cell's own area only, not a pin's */
    }
    if (f) fclose(f);
}

/* The area of one gate equivalent: NAND2_X1's, else the smallest cell
 * whose name holds NAND2. */
static int ge_cell(const char *dir, tb_sta *r, char *err, size_t errlen)
{
    lib_cell(dir, "nand2", "NAND2_X1", r->ge_cell, sizeof r->ge_cell, &r->ge_area);
    if (r->ge_area > 0) return TB_SYNTH_OK;
    snprintf(err, errlen, "synth: the Liberty file has no NAND2 cell with an area (the gate equivalent's measure)");
    return TB_SYNTH_BADINPUT;
}

/* ABC's constraints (dir/abc.constr): the library's smallest buffer
 * (BUF_X1, else the smallest cell named BUF) drives the inputs, the
 * outputs carry no load (as OpenSTA times them). ABC's `buffer` needs
 * them to repair the nets that drive more than their cell's max_capacitance
 * (docs/timing.md, "Design rules"). */
static int abc_constr(const char *dir, char *err, size_t errlen)
{
    char buf[64], path[PATH_MAX], text[200];
    double area;
    lib_cell(dir, "buf", "BUF_X1", buf, sizeof buf, &area);
    if (!(area > 0)) {
        snprintf(err, errlen, "synth: the Liberty file has no buffer cell (a name with BUF): the flow buffers high fan-out nets with it");
        return TB_SYNTH_BADINPUT;
    }
    snprintf(text, sizeof text, "set_driving_cell %s\nset_load 0\n", buf);
    snprintf(path, sizeof path, "%s/abc.constr", dir);
    return base_out_write_all(path, text, strlen(text), err, errlen) ? TB_SYNTH_BADINPUT : TB_SYNTH_OK;
}

/* Yosys's stat: "Number of cells: N" and "Chip area for module ...: A". */
static void read_stat(const char *dir, long *cells, double *area)
{
    char path[PATH_MAX], line[400];
    snprintf(path, sizeof path, "%s/stat.txt", dir);
    FILE *f = fopen(path, "r");
    *cells = -1;
    *area = -1;
    while (f && fgets(line, sizeof line, f)) {
        const char *c = strchr(line, ':');
        if (!c) continue;
        if (strstr(line, "Number of cells:")) *cells = atol(c + 1);
        if (strstr(line, "Chip area for module")) *area = atof(strrchr(line, ':') + 1);
    }
    if (f) fclose(f);
}

/* An instance of mapped.v by the net its Q output drives (a register's
 * name), else the name as it is (a port). */
static void q_net(const char *dir, char *name, size_t len)
{
    char path[PATH_MAX], line[400], pat[160];
    if (name[0] != '_') return;
    snprintf(path, sizeof path, "%s/mapped.v", dir);
    snprintf(pat, sizeof pat, " %s (", name);
    FILE *f = fopen(path, "r");
    int in = 0;
    while (f && fgets(line, sizeof line, f)) {
        if (!in) { in = strstr(line, pat) != NULL; continue; }
        const char *q = strstr(line, ".Q(");
        if (q) {
            q += 3;
            /* splitnets' one-bit wires are escaped names (\rg[15] and a blank) */
            if (*q == '\\') q++;
            snprintf(name, len, "%.*s", (int)strcspn(q, ") "), q);
            break;
        }
        if (strstr(line, ");")) break;
    }
    if (f) fclose(f);
}

/* OpenSTA's report_checks in ps: Startpoint/Endpoint, the pins along the
 * path ("DELAY TIME ^ INST/PIN (CELL)"), "T data arrival time", "-S library
 * setup time", "S slack". */
static int read_sta(const char *dir, tb_sta *r, char *err, size_t errlen)
{
    char path[PATH_MAX], line[512];
    snprintf(path, sizeof path, "%s/sta.log", dir);
    FILE *f = fopen(path, "r");
    int arrival = 0, slack = 0;
    char last_inst[160] = "";
    r->npath = 0;
    r->setup_ps = 0;
    while (f && fgets(line, sizeof line, f)) {
        double d, t;
        char edge, pin[160], cell[64];
        if (sscanf(line, "Startpoint: %127s (%31[^)]", r->start, r->start_kind) >= 1
            || sscanf(line, "Endpoint: %127s (%31[^)]", r->end, r->end_kind) >= 1) continue;
        /* (sscanf counts conversions only: the words are matched by strstr) */
        if (strstr(line, "data arrival time")) {
            if (!arrival && sscanf(line, " %lf", &t) == 1) { r->arrival_ps = t; arrival = 1; }
            continue;
        }
        if (strstr(line, "library setup time") && sscanf(line, " %lf", &d) == 1) { r->setup_ps = -d; continue; }
        if (strstr(line, " slack (") && sscanf(line, " %lf", &t) == 1) { r->slack_ps = t; slack = 1; continue; }
        if (arrival || sscanf(line, " %lf %lf %c %159s (%63[^)])", &d, &t, &edge, pin, cell) != 5) continue;
        if (edge != '^' && edge != 'v') continue;
        char *slash = strrchr(pin, '/');
        if (!slash) continue;       /* a port's own line */
        *slash = 0;
        if (!strcmp(pin, last_inst) || r->npath == TB_STA_CELLS) continue;
        snprintf(last_inst, sizeof last_inst, "%s", pin);
        snprintf(r->path[r->npath++], sizeof r->path[0], "%s", cell);
    }
    if (f) fclose(f);
    if (!arrival || !slack) {
        snprintf(err, errlen, "synth: OpenSTA reported no timed path (see sta.log: use --keep DIR)");
        return TB_SYNTH_FAILED;
    }
    q_net(dir, r->start, sizeof r->start);
    q_net(dir, r->end, sizeof r->end);
    r->crit_ps = r->period_ps - r->slack_ps;
    r->fmax_mhz = r->crit_ps > 0 ? 1e6 / r->crit_ps : 0;
    return TB_SYNTH_OK;
}

int tb_synth_sta(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fm, const char *liberty,
                 double period_ps, int abc, const char *dir, tb_synth_run *run, tb_sta *r, char *err, size_t errlen)
{
    memset(r, 0, sizeof *r);
    r->period_ps = period_ps;
    int rc = export_unit(u, cfg, fm, dir, err, errlen);
    if (rc) return rc;
    if (need_tool("sta", "opensta", err, errlen)) return TB_SYNTH_BADINPUT;
    if ((rc = liberty_in(liberty, dir, run, err, errlen)) || (rc = ge_cell(dir, r, err, errlen))
        || (rc = abc_constr(dir, err, errlen))) return rc;
    /* ABC's default script for a Liberty (Yosys's `abc -liberty`), or its
     * mapping alone (TB_ABC_LIGHT), then its `buffer -p`: the design-rule
     * repair every synthesis flow makes before timing (docs/timing.md,
     * "Design rules"); no timing-driven sizing. splitnets: one-bit wires,
     * so that no assignment to a concatenation is left, which OpenSTA's
     * Verilog reader refuses. */
    static const char *const script[2] = {
        "+strash;&get,-n;&fraig,-x;&put;scorr;dc2;dretime;strash;&get,-n;&dch,-f;&nf;&put;buffer,-p",
        "+strash;dretime;&get,-n;&nf;&put;buffer,-p",
    };
    char cmd[1200];
    snprintf(cmd, sizeof cmd, "yosys -q -l yosys.log -p 'read_verilog %s.v; synth -top %s; "
             "dfflibmap -liberty liberty.lib; abc -liberty liberty.lib -constr abc.constr "
             "-script %s; opt_clean; splitnets; opt_clean; "
             "tee -q -o stat.txt stat -liberty liberty.lib; write_verilog -noattr mapped.v' >/dev/null 2>&1",
             u->name, u->name, script[abc == TB_ABC_LIGHT]);
    rc = tb_synth_tool(run, "yosys", dir, cmd, 1, err, errlen);
    if (rc == TB_SYNTH_FAILED) return tool_failed(dir, "yosys.log", "yosys", err, errlen);
    if (rc) return rc;
    read_stat(dir, &r->cells, &r->area);
    if (r->area < 0) { snprintf(err, errlen, "synth: Yosys printed no chip area (see stat.txt: use --keep DIR)"); return TB_SYNTH_FAILED; }
    r->area_ge = r->area / r->ge_area;
    char tcl[1200], path[PATH_MAX];
    snprintf(tcl, sizeof tcl,
             "read_liberty liberty.lib\n"
             "set_cmd_units -time ps\n"
             "read_verilog mapped.v\n"
             "link_design %s\n"
             "create_clock -name clk -period %.1f [get_ports clk]\n"
             "set_input_delay 0 -clock clk [delete_from_list [all_inputs] [get_ports clk]]\n"
             "set_output_delay 0 -clock clk [all_outputs]\n"
             "report_checks -path_delay max -fields {nets} -digits 1\n"
             "exit\n", u->name, period_ps);
    snprintf(path, sizeof path, "%s/sta.tcl", dir);
    if (base_out_write_all(path, tcl, strlen(tcl), err, errlen)) return TB_SYNTH_BADINPUT;
    rc = tb_synth_tool(run, "sta", dir, "sta -no_init -exit sta.tcl >sta.log 2>&1", 0, err, errlen);
    if (rc == TB_SYNTH_FAILED) return tool_failed(dir, "sta.log", "sta", err, errlen);
    if (rc) return rc;
    return read_sta(dir, r, err, errlen);
}

/* ------------------------------------------------------------- iCE40 */

/* Yosys's stat after synth_ice40: the cells by type. */
static void read_ice40_stat(const char *dir, tb_fpga *r)
{
    char path[PATH_MAX], line[400], cell[64];
    long n;
    snprintf(path, sizeof path, "%s/stat.txt", dir);
    FILE *f = fopen(path, "r");
    while (f && fgets(line, sizeof line, f)) {
        if (sscanf(line, " %63s %ld", cell, &n) != 2 || strncmp(cell, "SB_", 3)) continue;
        if (!strcmp(cell, "SB_LUT4")) r->luts += n;
        else if (!strncmp(cell, "SB_DFF", 6)) r->ffs += n;
        else if (!strcmp(cell, "SB_CARRY")) r->carries += n;
        else if (!strcmp(cell, "SB_MAC16")) r->dsps += n;
        else if (!strncmp(cell, "SB_RAM40", 8)) r->rams += n;
    }
    if (f) fclose(f);
}

/* nextpnr's log: "ICESTORM_LC: U/ A", "SB_IO: U/ A", the last "Max
 * frequency for clock 'clk...': F MHz (PASS|FAIL at T MHz)" and "Max
 * delay A -> B: X ns" of the paths from or to ports (<async>; the last of
 * each kind: after routing). 1 if a frequency was found (for a design
 * without a clocked path, 1000 / its port to port delay). */
static int read_nextpnr(const char *dir, tb_fpga *r)
{
    char path[PATH_MAX], line[600];
    snprintf(path, sizeof path, "%s/nextpnr.log", dir);
    FILE *f = fopen(path, "r");
    int found = 0;
    while (f && fgets(line, sizeof line, f)) {
        const char *s;
        long a, b;
        if ((s = strstr(line, "ICESTORM_LC:")) && sscanf(s, "ICESTORM_LC: %ld/ %ld", &a, &b) == 2) { r->lcs = a; r->lcs_avail = b; }
        else if ((s = strstr(line, "SB_IO:")) && sscanf(s, "SB_IO: %ld/ %ld", &a, &b) == 2) { r->ios = a; r->ios_avail = b; }
        else if ((s = strstr(line, "Max frequency for clock 'clk")) && (s = strstr(s, "': "))) {
            double fm;
            char verdict[8];
            double at;
            if (sscanf(s, "': %lf MHz (%7s at %lf", &fm, verdict, &at) == 3) {
                r->fmax_mhz = fm;
                r->met = !strcmp(verdict, "PASS");
                r->target_mhz = at;
                r->clocked = found = 1;
            }
        } else if ((s = strstr(line, "Max delay ")) && (s = strstr(s, ": ")) && strstr(line, "<async>")) {
            const char *arrow = strstr(line, "->");
            double ns = atof(s + 2);
            if (!arrow) continue;
            int from_port = strstr(line, "<async>") < arrow, to_port = strstr(arrow, "<async>") != NULL;
            if (from_port && to_port) r->comb_ns = ns;
            else if (from_port) r->in_ns = ns;
            else r->out_ns = ns;
        }
    }
    if (f) fclose(f);
    if (!found && r->comb_ns > 0) { r->fmax_mhz = 1000 / r->comb_ns; found = 1; }
    return found;
}

int tb_synth_fpga(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fm, const char *dir,
                  tb_synth_run *run, tb_fpga *r, char *err, size_t errlen)
{
    r->luts = r->ffs = r->carries = r->dsps = r->rams = r->lcs = r->lcs_avail = r->ios = r->ios_avail = 0;
    r->fmax_mhz = r->target_mhz = r->in_ns = r->out_ns = r->comb_ns = 0;
    r->met = r->clocked = 0;
    /* the names go into nextpnr's command line: letters and digits only */
    if (!r->package[0] || strspn(r->package, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789") != strlen(r->package)
        || strspn(r->device, "abcdefghijklmnopqrstuvwxyz0123456789") != strlen(r->device)) {
        snprintf(err, errlen, "synth: --device %s --package %s: letters and digits only (e.g. hx8k, ct256)", r->device, r->package);
        return TB_SYNTH_BADINPUT;
    }
    int rc = export_unit(u, cfg, fm, dir, err, errlen);
    if (rc) return rc;
    if (need_tool("nextpnr-ice40", "nextpnr-ice40", err, errlen)) return TB_SYNTH_BADINPUT;
    char cmd[1200];
    snprintf(cmd, sizeof cmd, "yosys -q -l yosys.log -p 'read_verilog %s.v; synth_ice40 -top %s -json %s.json; "
             "tee -q -o stat.txt stat' >/dev/null 2>&1", u->name, u->name, u->name);
    rc = tb_synth_tool(run, "yosys", dir, cmd, 1, err, errlen);
    if (rc == TB_SYNTH_FAILED) return tool_failed(dir, "yosys.log", "yosys", err, errlen);
    if (rc) return rc;
    read_ice40_stat(dir, r);
    int n = snprintf(cmd, sizeof cmd, "nextpnr-ice40 --%s --package %s --json %s.json", r->device, r->package, u->name);
    if (r->freq_mhz > 0) n += snprintf(cmd + n, sizeof cmd - (size_t)n, " --freq %g", r->freq_mhz);
    snprintf(cmd + n, sizeof cmd - (size_t)n, " >nextpnr.log 2>&1");
    rc = tb_synth_tool(run, "nextpnr", dir, cmd, 0, err, errlen);
    if (rc != TB_SYNTH_OK && rc != TB_SYNTH_FAILED) return rc;
    /* a missed --freq target fails nextpnr's exit status, not the flow */
    if (read_nextpnr(dir, r)) return TB_SYNTH_OK;
    if (r->ios_avail > 0 && r->ios > r->ios_avail) {
        snprintf(err, errlen, "synth: %s needs %ld I/O cells, more than the %ld nextpnr finds on the %s in package %s "
                 "(choose a larger one: --device hx8k --package ct256)", u->name, r->ios, r->ios_avail, r->device, r->package);
        return TB_SYNTH_BADINPUT;
    }
    return tool_failed(dir, "nextpnr.log", "nextpnr", err, errlen);
}
