// harness.cpp - what a user who wants speed writes around Verilator: a C++
// main driving the Verilated model of the exported horner3 (`shadesim
// verilog horner3`, paper schedule, width 16) from the same text vector
// file `shadesim run` reads (docs/vectors.md), numbers parsed with
// std::from_chars, inputs quantized as shadesim does at these formats
// (a..d s7.9, t u1.15: truncation, i.e. floor, and wrap), then item after
// item through the valid/ready handshake, one line per output beat
// written as the generated testbench writes it ("CYCLE YYYY", hex), so
// that bench/verilog/run.sh checks it against shadesim's expected lines.
//
//   horner3_harness FILE.vec OUT
// prints on stderr the eval loop's own time (the simulation alone, the
// file already parsed): "eval SECONDS CLOCKS".
#include "Vhorner3.h"
#include "verilated.h"
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <vector>

static const int NIN = 5;
// fraction bits of a, b, c, d, t
static const int FBITS[NIN] = { 9, 9, 9, 9, 15 };

int main(int argc, char **argv)
{
    if (argc != 3) { std::fprintf(stderr, "usage: horner3_harness FILE.vec OUT\n"); return 2; }
    std::FILE *f = std::fopen(argv[1], "rb");
    if (!f) { std::perror(argv[1]); return 2; }
    std::vector<char> text;
    char buf[1 << 16];
    size_t got;
    while ((got = std::fread(buf, 1, sizeof buf, f)) > 0) text.insert(text.end(), buf, buf + got);
    std::fclose(f);
    text.push_back('\n');
    // every data line: five inputs, "|", the expected output (not needed here)
    std::vector<uint16_t> in;
    const char *p = text.data(), *end = p + text.size();
    while (p < end) {
        const char *eol = static_cast<const char *>(std::memchr(p, '\n', (size_t)(end - p)));
        if (*p != '#' && eol > p) {
            const char *q = p;
            for (int i = 0; i < NIN; i++) {
                while (q < eol && *q == ' ') q++;
                double x;
                auto r = std::from_chars(q, eol, x);
                if (r.ec != std::errc()) { std::fprintf(stderr, "bad number\n"); return 2; }
                q = r.ptr;
                in.push_back((uint16_t)(int64_t)std::floor(std::ldexp(x, FBITS[i])));
            }
        }
        p = eol + 1;
    }
    size_t items = in.size() / NIN;
    std::vector<uint64_t> beat_cycle(items);
    std::vector<uint16_t> beat_y(items);

    auto t0 = std::chrono::steady_clock::now();
    VerilatedContext ctx;
    Vhorner3 top(&ctx);
    top.clk = 0; top.rst = 1; top.in_valid = 0;
    top.eval();
    for (int k = 0; k < 2; k++) {               // reset, as the generated testbench: two edges
        top.clk = 1; top.eval();
        top.clk = 0; top.eval();
    }
    top.rst = 0;
    size_t next = 0, beats = 0;
    uint64_t cycle = 0, clocks = 2;
    auto offer = [&](size_t i) {
        const uint16_t *v = &in[i * NIN];
        top.a = v[0]; top.b = v[1]; top.c = v[2]; top.d = v[3]; top.t = v[4];
        top.in_valid = 1;
    };
    if (items) offer(0);
    top.eval();
    while (beats < items) {
        // the values before the edge are those of the cycle that ends
        int accepted = top.in_valid && top.in_ready;
        if (top.out_valid) {
            beat_cycle[beats] = cycle;
            beat_y[beats] = (uint16_t)top.y;
            beats++;
        }
        top.clk = 1; top.eval();                 // registers take the values before the edge
        clocks++;
        if (accepted) { next++; if (next < items) offer(next); else top.in_valid = 0; }
        top.clk = 0; top.eval();
        cycle++;
        if (cycle > 1000 + 4096 * (uint64_t)items) { std::fprintf(stderr, "no answer\n"); return 1; }
    }
    auto t1 = std::chrono::steady_clock::now();
    std::fprintf(stderr, "eval %.6f %llu\n", std::chrono::duration<double>(t1 - t0).count(),
                 (unsigned long long)clocks);
    std::FILE *o = std::fopen(argv[2], "wb");
    if (!o) { std::perror(argv[2]); return 2; }
    for (size_t i = 0; i < items; i++) std::fprintf(o, "%llu %04x\n", (unsigned long long)beat_cycle[i], (unsigned)beat_y[i]);
    if (std::fclose(o)) { std::perror(argv[2]); return 2; }
    top.final();
    return 0;
}
