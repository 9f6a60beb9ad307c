// horner3_width.v - horner3_hand.v with t declared 12 bits wide instead of 16,
// for the test that a port width mismatch is refused before simulating.
// The original text:
//
// the cubic Horner datapath of Nechyporuk & Romanyuk
// (2020), Fig. 9, with its six-step sequence, written by hand in plain
// Verilog-2001 with the ports and handshake of `shadesim verilog horner3`
// (docs/verilog.md), for `shadesim cosim horner3 --rtl` (tests/cli_rtl.sh).
// Not generated: a one-hot step ring instead of the export's counter and
// tables, so the check compares two different descriptions of one design.
//
//   MUL = MX1 * t         MX1: A in step 1, else RG
//   Sm  = MX2 + BK        MX2: B (step 0), C (step 3), D (step 5), else MUL
//   RG <= Sm              every clock; BK passes RG in steps 1, 3, 5, else 0
//   steps: RG <= B; A t + B; (.) t; (.) + C; (.) t; (.) + D = I
//
// Formats (shadesim's default rule, width 16, trunc/wrap): A, B, C, D, y and
// every datapath word s7.9 (two's complement, 9 fraction bits); t u1.15.
// MUL floors the exact product to 9 fraction bits and keeps its low 16 bits;
// the adder keeps the low 16 bits of the sum.
//
// Handshake: the unit waits in step 0 while in_valid is 0; in_ready is 1 in
// step 5, where the item (held on the inputs since step 0) is accepted;
// out_valid is 1 the clock after, while y = RG holds I. rst (synchronous,
// active high) returns to step 0 with RG = 0 and out_valid = 0.
module horner3_width (
    input  wire        clk,
    input  wire        rst,
    input  wire [15:0] a,
    input  wire [15:0] b,
    input  wire [15:0] c,
    input  wire [15:0] d,
    input  wire [11:0] t,   // WRONG WIDTH: the unit has 16 bits
    input  wire        in_valid,
    output wire        in_ready,
    output wire [15:0] y,
    output reg         out_valid
);
    reg  [5:0]  step;          // one-hot: step[k] is step k
    reg  [15:0] rg;

    // the multiplier: signed 16 x unsigned 16 (t widened by a 0), exact in
    // 33 bits; the product has 9 + 15 fraction bits, MUL keeps bits 30..15
    wire [15:0] mx1 = step[1] ? a : rg;
    wire signed [32:0] prod = $signed(mx1) * $signed({1'b0, t});
    wire [15:0] mul = prod[30:15];

    wire [15:0] mx2 = step[0] ? b : step[3] ? c : step[5] ? d : mul;
    wire [15:0] bk  = (step[1] | step[3] | step[5]) ? rg : 16'd0;
    wire [15:0] sm  = mx2 + bk;

    assign in_ready = step[5];
    assign y = rg;

    always @(posedge clk) begin
        if (rst) begin
            step      <= 6'b000001;
            rg        <= 16'd0;
            out_valid <= 1'b0;
        end else begin
            rg        <= sm;
            out_valid <= step[5];
            if (step[0]) step <= in_valid ? 6'b000010 : 6'b000001;
            else         step <= {step[4:0], step[5]};
        end
    end
endmodule
