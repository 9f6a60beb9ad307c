// horner3_late.v - horner3_hand.v re-timed: one more register stage after
// it, so y and out_valid come a clock later than shadesim's beats (the
// latency 7 clocks, not 6; still six clocks an item). Clock by clock it
// differs from the model at the first beat; item by item (cosim --match
// items) it is bit-exact. tests/cli_rtl.sh also puts horner3_bug.v behind
// the same stage.
module horner3_late (
    input  wire        clk,
    input  wire        rst,
    input  wire [15:0] a,
    input  wire [15:0] b,
    input  wire [15:0] c,
    input  wire [15:0] d,
    input  wire [15:0] t,
    input  wire        in_valid,
    output wire        in_ready,
    output reg  [15:0] y,
    output reg         out_valid
);
    wire [15:0] y0;
    wire        v0;
    horner3_hand core (.clk(clk), .rst(rst), .a(a), .b(b), .c(c), .d(d), .t(t), .in_valid(in_valid),
                       .in_ready(in_ready), .y(y0), .out_valid(v0));
    always @(posedge clk) begin
        y         <= y0;
        out_valid <= rst ? 1'b0 : v0;
    end
endmodule
