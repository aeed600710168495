// The normalize block as RTL (docs/rtl.md): N · (1/|N|) in fixed:I.F, bit for bit the
// fixed-point kernel of modules/normalize (formulas there), with the timing the model
// declares for the block: a pixel issued every II · work cycles (work 2 for the first
// pixel of a packet in forward-difference mode: the seed), valid LATENCY cycles after
// its work, up to ⌈(LATENCY + 1) / II⌉ pixels held between issue and hand-over.
//
// MODE  0 exact               r = N·N; s = 1 / sqrt(r)
//       1 forward-difference  r by second-order differences along the packet (in_direct:
//                             r = N·N, for bump packets); s = rsqrt(r), correctly rounded
//       2, 3, 4 rsqrt0|1|2    r = N·N; s = the float32 bit-trick estimate, then 0, 1 or 2
//                             Newton steps y ← y (3/2 − (r/2 · y) · y)
//
// Every operation rounds once, as the model's Fixed type: products to nearest (ties up),
// quotients to nearest (ties away from zero), square roots and conversions to nearest
// (even); results saturate. The datapath is one combinational step at issue, then the
// latency's registers (a synthesis tool that retimes spreads them over the logic).
//
// Written in the Verilog-2005 subset, with SystemVerilog's logic and always_ff, that
// both Yosys 0.23 and Verilator read (no typedefs, casts or return): assignments to a
// wider signed variable sign-extend on purpose, hence WIDTH off.
//
// Two modules: normalize_datapath, the arithmetic of one pixel (combinational), and
// normalize_unit, the block: the datapath, the radicand's sequence registers, and the
// issue, latency and hand-over of its timing.
/* verilator lint_off WIDTH */
module normalize_unit #(
    parameter integer IBITS = 3,
    parameter integer FBITS = 20,
    parameter integer MODE = 0,
    parameter integer LATENCY = 40,
    parameter integer II = 3,
    parameter integer TAG_W = 32
) (
    input  logic                          clk,
    input  logic                          rst,  // synchronous, active high
    // Pixels in: the normal, and with the first pixel of a packet ΔN_H and c = 2|ΔN_H|².
    input  logic                          in_valid,
    output logic                          in_ready,
    input  logic                          in_first,
    input  logic                          in_direct,
    input  logic [TAG_W-1:0]              in_tag,
    input  logic [IBITS+FBITS:0]          in_nx, in_ny, in_nz,
    input  logic [IBITS+FBITS:0]          in_dhx, in_dhy, in_dhz, in_c,
    // Unit normals out, in issue order.
    output logic                          out_valid,
    input  logic                          out_ready,
    output logic [TAG_W-1:0]              out_tag,
    output logic [IBITS+FBITS:0]          out_nx, out_ny, out_nz
);
  localparam integer W = 1 + IBITS + FBITS;  // bits of a word
  localparam integer CAPACITY = (LATENCY + 1 + II - 1) / II;
  localparam integer DUE_W = $clog2(2 * II + LATENCY + 1);
  localparam integer CNT_W = $clog2(CAPACITY + 1);
  localparam integer PTR_W = CAPACITY > 1 ? $clog2(CAPACITY) : 1;

  // ---- one pixel's arithmetic ----------------------------------------------------------
  logic [W-1:0] seq_r, seq_delta, seq_c;  // R and δ for the next pixel of the packet, c
  logic [W-1:0] result_x, result_y, result_z, next_r, next_delta;
  normalize_datapath #(.IBITS(IBITS), .FBITS(FBITS), .MODE(MODE)) datapath (
      .first(in_first), .direct(in_direct), .nx(in_nx), .ny(in_ny), .nz(in_nz),
      .dhx(in_dhx), .dhy(in_dhy), .dhz(in_dhz), .c(in_c), .seq_r(seq_r), .seq_delta(seq_delta), .seq_c(seq_c),
      .out_x(result_x), .out_y(result_y), .out_z(result_z), .next_r(next_r), .next_delta(next_delta));

  // ---- timing: issue, the latency, hand-over ------------------------------------------
  // Held pixels in a ring: result, tag, and cycles until valid (`due`).
  logic [W-1:0] held_x[CAPACITY], held_y[CAPACITY], held_z[CAPACITY];
  logic [TAG_W-1:0] held_tag[CAPACITY];
  logic [DUE_W-1:0] held_due[CAPACITY];
  logic [PTR_W-1:0] head, tail, head_next;
  logic [CNT_W-1:0] count, count_next;
  logic [DUE_W-1:0] busy;  // cycles until the next issue

  wire issue = in_valid && in_ready;
  wire hand_over = out_valid && out_ready;
  wire seeds = MODE == 1 && in_first;
  // Cycles from issue to valid, less one: II · (work − 1) + LATENCY − 1.
  wire [DUE_W-1:0] due_at_issue = (seeds ? II : 0) + LATENCY - 1;
  assign in_ready = busy == 0 && count < CAPACITY;

  function automatic [PTR_W-1:0] next(input [PTR_W-1:0] p);
    next = p == CAPACITY - 1 ? 0 : p + 1;
  endfunction

  always_comb begin
    head_next = hand_over ? next(head) : head;
    count_next = count + issue - hand_over;
  end

  integer k;
  always_ff @(posedge clk) begin
    if (rst) begin
      head <= 0;
      tail <= 0;
      count <= 0;
      busy <= 0;
      out_valid <= 0;
      seq_r <= 0;
      seq_delta <= 0;
      seq_c <= 0;
    end else begin
      for (k = 0; k < CAPACITY; k = k + 1)
        if (held_due[k] != 0) held_due[k] <= held_due[k] - 1;
      busy <= busy != 0 ? busy - 1 : 0;
      if (issue) begin
        held_x[tail] <= result_x;
        held_y[tail] <= result_y;
        held_z[tail] <= result_z;
        held_tag[tail] <= in_tag;
        held_due[tail] <= due_at_issue;
        tail <= next(tail);
        busy <= II * (seeds ? 2 : 1) - 1;
        if (MODE == 1) begin
          seq_r <= next_r;
          seq_delta <= next_delta;
          if (in_first) seq_c <= in_c;
        end
      end
      head <= head_next;
      count <= count_next;
      // Valid in the next cycle: the oldest pixel, once its cycles are done.
      out_valid <= count_next != 0 && (head_next == tail && issue ? due_at_issue == 0 : held_due[head_next] <= 1);
    end
  end

  assign out_tag = held_tag[head];
  assign out_nx = held_x[head];
  assign out_ny = held_y[head];
  assign out_nz = held_z[head];
endmodule
/* verilator lint_on WIDTH */
