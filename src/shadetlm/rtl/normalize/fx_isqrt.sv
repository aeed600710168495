// ⌊√v⌋ digit by digit (two bits of v a step), with the remainder v − ⌊√v⌋².
module fx_isqrt #(
    parameter integer N = 8
) (
    input  logic [2*N-1:0] v,
    output logic [N-1:0]   root,
    output logic [N+1:0]   rem
);
  always_comb begin : digits
    logic [N+1:0] r, test;
    logic [N-1:0] q;
    integer i;
    r = 0;
    q = 0;
    for (i = N - 1; i >= 0; i = i - 1) begin
      r = {r[N-1:0], v[2*i+:2]};
      test = {q, 2'b01};
      if (r >= test) begin
        r = r - test;
        q = {q[N-2:0], 1'b1};
      end else begin
        q = {q[N-2:0], 1'b0};
      end
    end
    root = q;
    rem = r;
  end
endmodule
