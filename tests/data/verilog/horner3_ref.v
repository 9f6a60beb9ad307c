// horner3_ref.v - the Horner datapath of Nechyporuk & Romanyuk (2020), Fig. 9, written by hand as RTL from
// the paper (not from the simulator or its export), to cross-check both.
//
//   MUL = MX1 * t            MX1 in {A, RG}
//   Sm  = MX2 + BK(RG)       MX2 in {MUL, B, C, D}; BK passes RG or forces 0
//   RG <= Sm                 every clock
//
// Formats as shadesim's default rule at width W: coefficients, y and every
// datapath signal s(W-F).F (two's complement, F fraction bits), t u1.(W-1).
// MUL keeps the product's bits [TF+W-1:TF]: floor to F fraction bits, then
// wrap to W bits (shadesim's trunc/wrap). The adder wraps.
//
// Controller: a 3-bit step counter walks the paper's six steps (sec. IV);
// it waits at step 0 until in_valid; in_ready is 1 in the last step (the
// item is accepted at that edge); out_valid is in_ready one clock later,
// when RG holds I.
module horner3_ref #(
    parameter W  = 16,          // datapath width
    parameter F  = 9,           // datapath fraction bits (s(W-F).F)
    parameter TW = W,           // width of t (u1.(TW-1))
    parameter TF = TW - 1       // fraction bits of t
) (
    input  wire                 clk,
    input  wire signed [W-1:0]  a, b, c, d,
    input  wire        [TW-1:0] t,
    input  wire                 in_valid,
    output wire                 in_ready,
    output wire signed [W-1:0]  y,
    output reg                  out_valid
);
    reg  [2:0] step = 3'd0;
    reg  signed [W-1:0] rg = {W{1'b0}};
    initial out_valid = 1'b0;

    // Control words of the paper schedule (unit_horner.c, h3_paper).
    reg        mx1_sel;     // 0: A, 1: RG
    reg  [1:0] mx2_sel;     // 0: MUL, 1: B, 2: C, 3: D
    reg        bk_pass;
    always @* begin
        case (step)
            3'd0:    begin mx1_sel = 1'b1; mx2_sel = 2'd1; bk_pass = 1'b0; end  // RG <= B
            3'd1:    begin mx1_sel = 1'b0; mx2_sel = 2'd0; bk_pass = 1'b1; end  // RG <= A t + B
            3'd2:    begin mx1_sel = 1'b1; mx2_sel = 2'd0; bk_pass = 1'b0; end  // RG <= (A t + B) t
            3'd3:    begin mx1_sel = 1'b1; mx2_sel = 2'd2; bk_pass = 1'b1; end  // RG <= .. + C
            3'd4:    begin mx1_sel = 1'b1; mx2_sel = 2'd0; bk_pass = 1'b0; end  // RG <= (..) t
            3'd5:    begin mx1_sel = 1'b1; mx2_sel = 2'd3; bk_pass = 1'b1; end  // RG <= I
            default: begin mx1_sel = 1'b1; mx2_sel = 2'd0; bk_pass = 1'b0; end
        endcase
    end
    assign in_ready = (step == 3'd5);

    wire signed [W-1:0]    mx1  = mx1_sel ? rg : a;
    wire signed [W+TW:0]   prod = mx1 * $signed({1'b0, t});   // exact
    wire signed [W-1:0]    mul  = prod[TF+W-1:TF];            // floor, wrap
    reg  signed [W-1:0]    mx2;
    always @* begin
        case (mx2_sel)
            2'd0: mx2 = mul;
            2'd1: mx2 = b;
            2'd2: mx2 = c;
            default: mx2 = d;
        endcase
    end
    wire signed [W-1:0]    bk = bk_pass ? rg : {W{1'b0}};
    wire signed [W-1:0]    sm = mx2 + bk;                     // wraps

    wire [2:0] step_next = (step == 3'd0 && !in_valid) ? 3'd0
                         : (step == 3'd5) ? 3'd0 : step + 3'd1;
    always @(posedge clk) begin
        step      <= step_next;
        rg        <= sm;
        out_valid <= in_ready;
    end
    assign y = rg;
endmodule
