// horner3_ref_tb.v - Icarus Verilog testbench for horner3_ref.v: the same
// valid/ready driving as testbench/tb_run.c, from a file of quantized
// inputs (one item a line: a b c d t as hex raws of the formats' widths).
//
//   iverilog -g2005 -P horner3_ref_tb.W=16 -o tb horner3_ref_tb.v horner3_ref.v
//   vvp tb +in=INPUTS.hex +out=OUT.txt
//
// OUT: one line per output, "CYCLE Y" (the cycle it was valid in, counting
// from 0 as shadesim does; Y the signed raw of RG in decimal).
`timescale 1ns/1ps
module horner3_ref_tb;
    parameter W  = 16;             // datapath width: s7.(W-7), t u1.(W-1)
    parameter F  = W - 7;
    parameter MAXN = 1 << 18;      // most items the memory holds (-P to change)

    reg clk = 1'b0;
    reg signed [W-1:0] a, b, c, d;
    reg        [W-1:0] t;
    reg in_valid;
    wire in_ready, out_valid;
    wire signed [W-1:0] y;

    horner3_ref #(.W(W), .F(F), .TW(W)) dut (
        .clk(clk), .a(a), .b(b), .c(c), .d(d), .t(t), .in_valid(in_valid),
        .in_ready(in_ready), .y(y), .out_valid(out_valid));

    reg [W-1:0] mem_a [0:MAXN-1];
    reg [W-1:0] mem_b [0:MAXN-1];
    reg [W-1:0] mem_c [0:MAXN-1];
    reg [W-1:0] mem_d [0:MAXN-1];
    reg [W-1:0] mem_t [0:MAXN-1];
    integer n, got, next, cycle, fin, fout, r;
    reg [1023:0] inpath, outpath;
    reg [W-1:0] va, vb, vc, vd, vt;
    reg accepted;

    task offer(input integer k);
        begin
            a = mem_a[k]; b = mem_b[k]; c = mem_c[k]; d = mem_d[k]; t = mem_t[k];
        end
    endtask

    initial begin
        if (!$value$plusargs("in=%s", inpath)) begin $display("horner3_tb: +in=FILE missing"); $finish; end
        if (!$value$plusargs("out=%s", outpath)) outpath = "horner3_tb.out";
        fin = $fopen(inpath, "r");
        if (fin == 0) begin $display("horner3_tb: cannot open input"); $finish; end
        n = 0;
        r = 5;
        while (r == 5 && n < MAXN) begin
            r = $fscanf(fin, "%h %h %h %h %h\n", va, vb, vc, vd, vt);
            if (r == 5) begin
                mem_a[n] = va; mem_b[n] = vb; mem_c[n] = vc; mem_d[n] = vd; mem_t[n] = vt;
                n = n + 1;
            end
        end
        $fclose(fin);
        fout = $fopen(outpath, "w");
        // Time 0: the driver offers item 0 (shadesim's initialization run).
        got = 0; next = 0; cycle = 0;
        offer(0);
        in_valid = (n > 0);
        #1;
        while (got < n && cycle < 1000 + 4096 * n) begin
            // Before the edge: what the monitor samples and the handshake sees.
            accepted = in_valid && in_ready;
            if (out_valid) begin
                $fdisplay(fout, "%0d %0d", cycle, y);
                got = got + 1;
            end
            clk = 1'b1;
            #1;
            cycle = cycle + 1;
            if (accepted) next = next + 1;
            if (next < n) offer(next); else in_valid = 1'b0;
            #4 clk = 1'b0;
            #5;
        end
        $fclose(fout);
        $display("horner3_tb: %0d items, %0d clocks", got, cycle);
        $finish;
    end
endmodule
