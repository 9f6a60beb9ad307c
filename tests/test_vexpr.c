/* test_vexpr.c - logic elements' Verilog texts evaluated (fn=verilog,
 * testbench/tb_vexpr.h): each text against the same function written in C
 * with Verilog's rules worked out by hand (widths, signed compares,
 * selects, concatenation, replication, shifts, ?:, a function's and an
 * always block's case), on every input of narrow ones and random draws of
 * wide ones; and malformed texts refused with the character. */
#include "tests/tst.h"
#include "testbench/tb_vexpr.h"
#include <stdint.h>
#include <string.h>

static uint64_t rng = 0x2545f4914f6cdd1dull;
static uint64_t draw(void) { rng ^= rng << 13; rng ^= rng >> 7; rng ^= rng << 17; return rng; }
static uint64_t mk(int w) { return w >= 64 ? UINT64_MAX : ((uint64_t)1 << w) - 1; }
static int64_t sx(uint64_t v, int w) { return (int64_t)(v << (64 - w)) >> (64 - w); }

/* The C side of each case: inputs' raws (unsigned, their widths) to the
 * output's raw bits. */
static uint64_t c_le(const uint64_t *x) { return x[0] <= 0x8000; }
static uint64_t c_sle(const uint64_t *x) { return sx(x[0], 23) <= 0x200000; }
static uint64_t c_zero(const uint64_t *x) { return x[0] == 0 ? 0x40000 : x[0]; }
static uint64_t c_pos(const uint64_t *x) { return !(x[0] >> 31 & 1) && x[0] != 0; }
static uint64_t c_ge_ext(const uint64_t *x) { return x[0] >= x[1]; }
static uint64_t c_clamp(const uint64_t *x)
{
    int64_t v = sx(x[0], 32);
    return v < 0 ? 2 : v >= 0x10000000 ? 1 : 0;
}
static uint64_t c_shift(const uint64_t *x) { return (x[0] << 2 >> x[1]) & mk(19); }
static uint64_t c_sat(const uint64_t *x)
{
    /* {{2{x[15]}}, x, 3'b0} + 21'h1c000 kept to 21 bits, clamped to
     * [0, 0x38000] as signed, then bits [20:2] sign-extended to 20 */
    uint64_t w = (((uint64_t)(x[0] >> 15 & 1) * 3) << 19 | x[0] << 3);
    w = (w + 0x1c000) & mk(21);
    int64_t s = sx(w, 21);
    uint64_t v = s < 0 ? 0 : s > 0x38000 ? 0x38000 : w;
    int64_t t = sx(v >> 2 & mk(19), 19);
    return t < 0 ? 0 : t > 0xffff ? 0xffff : (uint64_t)t & 0xffff;
}
static uint64_t c_lead(const uint64_t *x)
{
    for (int b = 22; b >= 17; b--) if (x[0] >> b & 1) return (uint64_t)(b - 16);
    return 0;
}
static uint64_t c_norm(const uint64_t *x)
{
    int l = (int)c_lead(x);
    return x[0] >> (l + 1) & 0xffff;
}
static uint64_t c_rom(const uint64_t *x) { uint64_t i = (x[0] << 2 | x[1]) & 15; return i * i + 1; }

static const struct vcase {
    const char *text;
    int nin, w[2], out;
    uint64_t (*c)(const uint64_t *);
} cases[] = {
    { "assign %y = %0 <= 17'h8000;", 1, { 17 }, 1, c_le },
    { "assign %y = $signed(%0) <= $signed(23'h200000);", 1, { 23 }, 1, c_sle },
    { "assign %y = (%0 == 19'd0) ? 19'h40000 : %0;", 1, { 19 }, 19, c_zero },
    { "assign %y = (~%0[31] & (|%0));", 1, { 32 }, 1, c_pos },
    { "assign %y = %0 >= {1'd0, %1};", 2, { 22, 21 }, 1, c_ge_ext },
    { "assign %y = $signed(%0) < 0 ? 2'd2 : ($signed(%0) >= $signed(32'h10000000) ? 2'd1 : 2'd0);", 1, { 32 }, 2, c_clamp },
    { "wire [38:0] %t_e = {{20{1'b0}}, %0, 2'b0};\nwire [38:0] %t_s = %t_e >> %1;\nassign %y = {%t_s[18:0]};\n", 2, { 17, 4 }, 19,
      c_shift },
    { "wire [20:0] %t_w = {{{2{%0[15]}}, %0}, 3'b0} + 21'h1c000;\n"
      "wire [20:0] %t_v = $signed(%t_w) < $signed(21'b0) ? 21'b0 : $signed(%t_w) > $signed(21'h38000) ? 21'h38000 : %t_w;\n"
      "wire [21:0] %t_a = {{1{%t_v[20]}}, %t_v};\nwire [19:0] %t_s = %t_a[21:2];\n"
      "assign %y = $signed(%t_s) < $signed(20'h0) ? 16'h0 : $signed(%t_s) > $signed(20'hffff) ? 16'hffff : %t_s[15:0];\n",
      1, { 16 }, 16, c_sat },
    /* a wire used before its line, as Verilog allows */
    { "wire [2:0] %t_r = %t_l[2:0];\nwire [6:0] %t_l = %0[22] ? 7'd6 : %0[21] ? 7'd5 : %0[20] ? 7'd4 : %0[19] ? 7'd3 : "
      "%0[18] ? 7'd2 : %0[17] ? 7'd1 : 7'd0;\nassign %y = %t_r;\n", 1, { 23 }, 3, c_lead },
    { "wire [6:0] %t_l = %0[22] ? 7'd6 : %0[21] ? 7'd5 : %0[20] ? 7'd4 : %0[19] ? 7'd3 : %0[18] ? 7'd2 : %0[17] ? 7'd1 : 7'd0;\n"
      "wire [23:0] %t_e = {{1{1'b0}}, %0};\nreg [15:0] %t_r;\nalways @* begin\n    case (%t_l)\n"
      "        7'd0: %t_r = %t_e[16:1];\n        7'd1: %t_r = %t_e[17:2];\n        7'd2: %t_r = %t_e[18:3];\n"
      "        7'd3: %t_r = %t_e[19:4];\n        7'd4: %t_r = %t_e[20:5];\n        7'd5: %t_r = %t_e[21:6];\n"
      "        7'd6: %t_r = %t_e[22:7];\n        default: %t_r = 16'b0;\n    endcase\nend\nassign %y = %t_r;\n",
      1, { 23 }, 16, c_norm },
    { "function [7:0] %t_rom;\ninput [3:0] i;\ncase (i)\n    4'h0: %t_rom = 8'd1;\n    4'h1: %t_rom = 8'd2;\n"
      "    4'h2: %t_rom = 8'd5;\n    4'h3: %t_rom = 8'd10;\n    4'h4: %t_rom = 8'd17;\n    4'h5: %t_rom = 8'd26;\n"
      "    4'h6: %t_rom = 8'd37;\n    4'h7: %t_rom = 8'd50;\n    4'h8: %t_rom = 8'd65;\n    4'h9: %t_rom = 8'd82;\n"
      "    4'ha: %t_rom = 8'd101;\n    4'hb: %t_rom = 8'd122;\n    4'hc: %t_rom = 8'd145;\n    4'hd: %t_rom = 8'd170;\n"
      "    4'he: %t_rom = 8'd197;\n    4'hf: %t_rom = 8'd226;\nendcase\nendfunction\nassign %y = %t_rom({%0, %1});\n",
      2, { 2, 2 }, 8, c_rom },
};

static void t_against_c(void)
{
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        const struct vcase *v = &cases[k];
        char err[300];
        tb_vexpr *p = tb_vexpr_compile(v->text, v->nin, v->w, v->out, err, sizeof err);
        TST_CHECK(p != NULL, "case %zu: %s", k, err);
        if (!p) continue;
        int bits = v->w[0] + (v->nin > 1 ? v->w[1] : 0), bad = 0;
        long n = bits <= 16 ? 1L << bits : 20000;
        for (long j = 0; j < n && bad < 3; j++) {
            uint64_t x[2];
            int64_t in[2];
            for (int i = 0; i < v->nin; i++) {
                uint64_t r = bits <= 16 ? (uint64_t)j >> (i ? 0 : (v->nin > 1 ? v->w[1] : 0)) : j < 2 ? (j ? UINT64_MAX : 0) : draw();
                x[i] = r & mk(v->w[i]);
                in[i] = (int64_t)x[i];
            }
            uint64_t got = (uint64_t)tb_vexpr_fn(in, p), want = v->c(x) & mk(v->out);
            if (got != want) {
                TST_CHECK(0, "case %zu at %llx %llx: %llx, C gives %llx", k, (unsigned long long)x[0],
                          (unsigned long long)(v->nin > 1 ? x[1] : 0), (unsigned long long)got, (unsigned long long)want);
                bad++;
            }
        }
        tb_vexpr_free(p);
    }
}

static void t_malformed(void)
{
    static const struct { const char *text; const char *msg; } bad[] = {
        { "assign %y = %0 <;", "verilog text, at character 17: an operand expected" },
        { "assign %y = %2;", "verilog text, at character 15: no such input" },
        { "wire [3:0] %t_a = %0;", "verilog text, at character 22: no assign %y = ...;" },
        { "assign %y = %t_b;", "verilog text, at character 18: %t_b is not declared" },
        { "assign %y = {%0, %0", "verilog text, at character 20: '}' expected" },
        { "always @* begin end", "verilog text, at character 1: wire, reg, function or assign expected" },
        { "wire [3:1] %t_a = %0; assign %y = %t_a;", "verilog text, at character 10: a range [H:0] within 64 bits expected" },
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        char err[300] = "";
        int w[1] = { 8 };
        tb_vexpr *p = tb_vexpr_compile(bad[k].text, 1, w, 8, err, sizeof err);
        TST_CHECK(!p, "%s: accepted", bad[k].text);
        tb_vexpr_free(p);
        TST_EQ_STR(err, bad[k].msg);
    }
    /* nesting past the parser's depth: refused, not a crash */
    char deep[700] = "assign %y = ";
    memset(deep + 12, '(', 400);
    strcpy(deep + 412, "%0;");
    char err[300];
    int w[1] = { 8 };
    tb_vexpr *p = tb_vexpr_compile(deep, 1, w, 8, err, sizeof err);
    TST_CHECK(!p && strstr(err, "nested too deep"), "%s", err);
}

int main(void)
{
    TST_RUN(t_against_c);
    TST_RUN(t_malformed);
    TST_EXIT();
}
