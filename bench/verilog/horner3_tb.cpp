// horner3_tb.cpp - Verilator harness for bench/verilog/horner3.v: the same
// job as `shadesim run horner3 --vectors FILE` minus the error report.
//
// Reads a shadesim vector file (text, '#' comments, "a b c d t | y" rows),
// parses every number with strtod as shadesim does, quantizes the inputs
// exactly like the testbench (trunc = floor(x * 2^F), then wrap to the
// format's width), drives the model through the same valid/ready handshake
// as testbench/tb_run.c, and writes each output's raw integer, one a line.
//
//   horner3_tb VECTORS [OUT|-] [--raw-in HEXFILE]
//
// OUT defaults to stdout. --raw-in also writes the quantized inputs in hex,
// one item a line (the Icarus testbench's input).
#include "Vhorner3.h"
#include "verilated.h"
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#ifndef HW
#define HW 16           // datapath width W
#endif
#define HF (HW - 7)     // datapath fraction bits: s7.(W-7)
#define TFB (HW - 1)    // t: u1.(W-1)

// floor(x * 2^f), wrapped to w bits (signed or not): sim_fx_from_real with
// trunc/wrap. ldexp and floor are exact; fmod by 2^w is exact too.
static int64_t quant(double x, int f, int w, bool is_signed)
{
    double v = std::floor(std::ldexp(x, f));
    if (!std::isfinite(v)) return 0;       // |x 2^f| >= 2^1024: its low w bits are 0
    double m = std::ldexp(1.0, w);
    v = std::fmod(v, m);                    // (-2^w, 2^w), exact
    if (v < 0) v += m;                      // [0, 2^w)
    uint64_t u = (uint64_t)v;
    if (is_signed && (u >> (w - 1))) return (int64_t)u - ((int64_t)1 << w);
    return (int64_t)u;
}

static char *slurp(const char *path, size_t *n)
{
    FILE *f = std::strcmp(path, "-") ? std::fopen(path, "rb") : stdin;
    if (!f) { std::perror(path); std::exit(2); }
    size_t cap = 1 << 20, len = 0;
    char *b = (char *)std::malloc(cap + 1);
    for (;;) {
        if (len == cap) { cap *= 2; b = (char *)std::realloc(b, cap + 1); }
        size_t k = std::fread(b + len, 1, cap - len, f);
        if (!k) break;
        len += k;
    }
    if (f != stdin) std::fclose(f);
    b[len] = 0;
    *n = len;
    return b;
}

int main(int argc, char **argv)
{
    if (argc < 2) { std::fprintf(stderr, "usage: %s VECTORS [OUT|-] [--raw-in HEXFILE]\n", argv[0]); return 2; }
    const char *outp = "-", *rawp = nullptr;
    for (int i = 2; i < argc; i++) {
        if (!std::strcmp(argv[i], "--raw-in") && i + 1 < argc) rawp = argv[++i];
        else outp = argv[i];
    }
    size_t len;
    char *text = slurp(argv[1], &len);

    // Rows: 5 inputs, '|', 1 expected output (ignored here).
    std::vector<int64_t> in;
    in.reserve(len / 80 * 5 + 16);
    long line = 0;
    for (char *p = text, *e = text + len; p < e;) {
        char *nl = (char *)std::memchr(p, '\n', (size_t)(e - p));
        if (!nl) nl = e;
        line++;
        *nl = 0;
        char *q = p;
        while (*q == ' ' || *q == '\t') q++;
        if (*q && *q != '#' && *q != '\r') {
            for (int i = 0; i < 5; i++) {
                char *end;
                double x = std::strtod(q, &end);
                if (end == q) { std::fprintf(stderr, "%s:%ld: bad row\n", argv[1], line); return 2; }
                q = end;
                in.push_back(i < 4 ? quant(x, HF, HW, true) : quant(x, TFB, HW, false));
            }
            while (*q == ' ' || *q == '\t') q++;
            if (*q != '|') { std::fprintf(stderr, "%s:%ld: missing '|'\n", argv[1], line); return 2; }
            char *end;
            (void)std::strtod(q + 1, &end);   // the expected output: parsed, as shadesim does
            if (end == q + 1) { std::fprintf(stderr, "%s:%ld: bad row\n", argv[1], line); return 2; }
        }
        p = nl + 1;
    }
    std::free(text);
    size_t n = in.size() / 5;
    if (!n) { std::fprintf(stderr, "%s: no vector rows\n", argv[1]); return 2; }

    if (rawp) {
        FILE *r = std::fopen(rawp, "w");
        if (!r) { std::perror(rawp); return 2; }
        uint64_t mask = HW == 64 ? ~(uint64_t)0 : (((uint64_t)1 << HW) - 1);
        for (size_t k = 0; k < n; k++)
            std::fprintf(r, "%llx %llx %llx %llx %llx\n",
                         (unsigned long long)(in[5 * k] & mask), (unsigned long long)(in[5 * k + 1] & mask),
                         (unsigned long long)(in[5 * k + 2] & mask), (unsigned long long)(in[5 * k + 3] & mask),
                         (unsigned long long)(in[5 * k + 4] & mask));
        if (std::fclose(r)) { std::perror(rawp); return 2; }
    }

    VerilatedContext *ctx = new VerilatedContext;
    ctx->commandArgs(argc, argv);
    Vhorner3 *top = new Vhorner3{ctx};
    std::vector<int64_t> y(n);
    std::vector<uint64_t> cyc(n);

    // Time 0: the driver offers item 0 (shadesim's initialization run).
    size_t next = 0, got = 0;
    auto offer = [&](size_t k) {
        top->a = (uint32_t)in[5 * k]; top->b = (uint32_t)in[5 * k + 1];
        top->c = (uint32_t)in[5 * k + 2]; top->d = (uint32_t)in[5 * k + 3];
        top->t = (uint32_t)in[5 * k + 4];
    };
    top->clk = 0;
    offer(0);
    top->in_valid = 1;
    top->eval();
    uint64_t clocks = 0, max_clocks = 1000 + (uint64_t)n * 4096;
    const int sh = 64 - HW;
    while (got < n && clocks < max_clocks) {
        // Values before the edge: what the monitor samples and what the
        // driver's handshake looks at.
        bool accepted = top->in_valid && top->in_ready;
        if (top->out_valid) {
            y[got] = (int64_t)((uint64_t)top->y << sh) >> sh;
            cyc[got] = clocks;
            got++;
        }
        top->clk = 1;
        top->eval();
        clocks++;
        if (accepted) next++;
        if (next < n) offer(next); else top->in_valid = 0;
        top->clk = 0;
        top->eval();
    }
    top->final();

    FILE *o = std::strcmp(outp, "-") ? std::fopen(outp, "w") : stdout;
    if (!o) { std::perror(outp); return 2; }
    static char buf[1 << 16];
    std::setvbuf(o, buf, _IOFBF, sizeof buf);
    for (size_t k = 0; k < got; k++) std::fprintf(o, "%lld\n", (long long)y[k]);
    std::fflush(o);
    std::fprintf(stderr, "verilator horner3: %zu items, %llu clocks, %.3g clocks/item\n", got,
                 (unsigned long long)clocks, got > 1 ? (double)(cyc[got - 1] - cyc[0]) / (double)(got - 1) : 0.0);
    delete top;
    delete ctx;
    return got == n ? 0 : 1;
}
