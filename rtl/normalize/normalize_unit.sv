// The normalize block as RTL (docs/rtl.md): N · (1/|N|) in fixed:I.F, bit for bit the
// fixed-point kernel of modules/normalize (formulas there), with the timing the model
// declares for it: a pixel issued every II · work cycles (work 2 for the first pixel of a
// packet in forward-difference mode: the seed), done LATENCY cycles after its work,
// up to CAPACITY pixels held between issue and hand-over.
//
// MODE  0 exact               r = N·N; s = 1 / sqrt(r)
//       1 forward-difference  r by second-order differences along the packet (in_direct:
//                             r = N·N, for bump packets); s = rsqrt(r), correctly rounded
//       2, 3, 4 rsqrt0|1|2    r = N·N; s = the float32 bit-trick estimate, then 0, 1 or 2
//                             Newton steps y ← y (3/2 − (r/2 · y) · y)
//
// Every operation rounds once, as the model's Fixed type: products to nearest (ties up),
// quotients to nearest (ties away from zero), square roots and conversions to nearest
// (even); results saturate. The datapath is one combinational step at issue, followed by
// the latency's registers (a synthesis tool that retimes spreads them over the logic).
module normalize_unit #(
    parameter int IBITS = 3,
    parameter int FBITS = 20,
    parameter int MODE = 0,
    parameter int LATENCY = 40,
    parameter int II = 3,
    parameter int TAG_W = 32,
    localparam int W = 1 + IBITS + FBITS  // bits of a word
) (
    input  logic               clk,
    input  logic               rst,        // synchronous, active high
    // Pixels in: the normal, and with the first pixel of a packet ΔN_H and c = 2|ΔN_H|².
    input  logic               in_valid,
    output logic               in_ready,
    input  logic               in_first,
    input  logic               in_direct,
    input  logic [TAG_W-1:0]   in_tag,
    input  logic [W-1:0]       in_nx, in_ny, in_nz,
    input  logic [W-1:0]       in_dhx, in_dhy, in_dhz, in_c,
    // Unit normals out, in issue order.
    output logic               out_valid,
    input  logic               out_ready,
    output logic [TAG_W-1:0]   out_tag,
    output logic [W-1:0]       out_nx, out_ny, out_nz
);
  localparam int CAPACITY = (LATENCY + 1 + II - 1) / II;  // ⌈(L + 1) / II⌉
  localparam int DUE_W = $clog2(2 * II + LATENCY + 1);
  localparam int CNT_W = $clog2(CAPACITY + 1);
  localparam int PTR_W = CAPACITY > 1 ? $clog2(CAPACITY) : 1;

  typedef logic signed [W-1:0] fx_t;
  localparam fx_t MAX = fx_t'({1'b0, {(W - 1) {1'b1}}});
  localparam fx_t MIN = fx_t'({1'b1, {(W - 1) {1'b0}}});

  // ---- fixed-point operations ---------------------------------------------------------
  // x saturated to the format (x of any width up to 4W + 8 bits, sign-extended).
  localparam int WIDE = 4 * W + 8;
  typedef logic signed [WIDE-1:0] wide_t;
  function automatic fx_t sat(input wide_t x);
    if (x > wide_t'(MAX)) return MAX;
    if (x < wide_t'(MIN)) return MIN;
    return fx_t'(x);
  endfunction
  // A constant k·2^-FBITS of the format (saturated where the format cannot hold it).
  function automatic fx_t konst(input longint k_scaled);
    return sat(wide_t'(k_scaled));
  endfunction
  localparam longint ONE_RAW = longint'(1) << FBITS;
  function automatic fx_t add(input fx_t a, input fx_t b);
    return sat(wide_t'(a) + wide_t'(b));
  endfunction
  function automatic fx_t sub(input fx_t a, input fx_t b);
    return sat(wide_t'(a) - wide_t'(b));
  endfunction
  function automatic fx_t mul(input fx_t a, input fx_t b);
    wide_t p = wide_t'(a) * wide_t'(b) + (wide_t'(1) <<< (FBITS - 1));
    return sat(p >>> FBITS);  // round half up
  endfunction
  function automatic fx_t div(input fx_t a, input fx_t b);
    wide_t n, d, q, r, ar, ad;
    if (b == 0) return a == 0 ? fx_t'(0) : (a > 0 ? MAX : MIN);
    n = wide_t'(a) <<< FBITS;
    d = wide_t'(b);
    q = n / d;  // toward zero
    r = n % d;  // with the dividend's sign
    ar = r < 0 ? -r : r;
    ad = d < 0 ? -d : d;
    if (2 * ar >= ad) q = ((n < 0) == (d < 0)) ? q + 1 : q - 1;  // ties away from zero
    return sat(q);
  endfunction

  // ⌊√v⌋ digit by digit, with the remainder v − ⌊√v⌋².
  localparam int RAD_W = 4 * W + 8;  // radicands: up to 3·FBITS + 1 bits
  typedef logic [RAD_W-1:0] rad_t;
  function automatic rad_t isqrt(input rad_t v, output rad_t rem);
    rad_t root = 0, test;
    rem = 0;
    for (int i = RAD_W / 2 - 1; i >= 0; i--) begin
      rem = (rem << 2) | rad_t'((v >> (2 * i)) & 3);
      test = (root << 2) | 1;
      if (rem >= test) begin
        rem = rem - test;
        root = (root << 1) | 1;
      end else begin
        root = root << 1;
      end
    end
    return root;
  endfunction
  // √x: √(x·2^F) in raw units; a negative x gives 0.
  function automatic fx_t fx_sqrt(input fx_t x);
    rad_t rem, s;
    if (x < 0) return 0;
    s = isqrt(rad_t'(x) << FBITS, rem);
    if (rem > s) s = s + 1;  // √v > s + ½
    return sat(wide_t'(s));
  endfunction
  // 1/√x: √(2^3F / x) in raw units; x ≤ 0 gives the largest value.
  function automatic fx_t fx_rsqrt(input fx_t x);
    rad_t n, d, q, rq, rem, s;
    if (x <= 0) return MAX;
    n = rad_t'(1) << (3 * FBITS);
    d = rad_t'(x);
    q = n / d;
    rq = n % d;
    s = isqrt(q, rem);
    if (rem > s || (rem == s && 4 * rq > d)) s = s + 1;
    return s > rad_t'(MAX) ? MAX : fx_t'(s);
  endfunction

  // ---- the float32 estimate (a table in silicon) --------------------------------------
  // x·2^-F as float32 bits, rounded to nearest even.
  function automatic logic [31:0] to_float_bits(input fx_t x);
    logic [W-1:0] m;
    logic [W+23:0] shifted;
    logic [24:0] mant;
    int p, e, sh;
    logic sign;
    if (x == 0) return 32'h0;
    sign = x < 0;
    m = sign ? W'(-x) : W'(x);
    p = 0;
    for (int i = 0; i < W; i++) if (m[i]) p = i;
    e = p - FBITS + 127;
    if (p <= 23) begin
      mant = 25'(m) << (23 - p);
    end else begin
      sh = p - 23;
      shifted = (W + 24)'(m);
      mant = 25'(shifted >> sh);
      // round to nearest even on the bits shifted out
      if (((shifted >> (sh - 1)) & 1) == 1 &&
          ((shifted & ((((W + 24)'(1)) << (sh - 1)) - 1)) != 0 || mant[0]))
        mant = mant + 1;
      if (mant[24]) begin
        mant = mant >> 1;
        e = e + 1;
      end
    end
    return {sign, 8'(e), mant[22:0]};
  endfunction
  // Float32 bits to the format, rounded to nearest even; NaN gives 0, infinities saturate.
  function automatic fx_t from_float_bits(input logic [31:0] b);
    logic [23:0] sig;
    int k;
    wide_t v, half, low;
    logic sign = b[31];
    if (b[30:23] == 8'hff) return b[22:0] != 0 ? fx_t'(0) : (sign ? MIN : MAX);
    sig = b[30:23] == 0 ? {1'b0, b[22:0]} : {1'b1, b[22:0]};
    k = (b[30:23] == 0 ? 1 : int'(b[30:23])) - 150 + FBITS;  // value·2^F = sig·2^k
    if (sig == 0) return 0;
    if (k >= 0) begin
      if (k > WIDE - 26) return sign ? MIN : MAX;
      v = wide_t'(sig) <<< k;
    end else if (-k > 25) begin
      v = 0;
    end else begin
      v = wide_t'(sig) >>> (-k);
      half = wide_t'(1) <<< (-k - 1);
      low = wide_t'(sig) & ((wide_t'(1) <<< (-k)) - 1);
      if (low > half || (low == half && v[0])) v = v + 1;
    end
    return sat(sign ? -v : v);
  endfunction
  function automatic fx_t rsqrt_newton(input fx_t r, input int steps);
    fx_t y = from_float_bits(32'h5f3759df - (to_float_bits(r) >> 1));
    fx_t half_r = mul(konst(ONE_RAW / 2), r);
    for (int i = 0; i < steps; i++) y = mul(y, sub(konst(3 * ONE_RAW / 2), mul(mul(half_r, y), y)));
    return y;
  endfunction

  // ---- one pixel ----------------------------------------------------------------------
  function automatic fx_t radicand(input fx_t x, input fx_t y, input fx_t z);
    return add(add(mul(x, x), mul(y, y)), mul(z, z));
  endfunction

  // The forward-difference sequence: R and δ for the next pixel of the packet.
  fx_t seq_r, seq_delta, seq_c;
  fx_t r_now, scale, seed_r, seed_delta;
  always_comb begin
    seed_r = radicand(in_nx, in_ny, in_nz);
    seed_delta = add(mul(konst(2 * ONE_RAW), add(add(mul(in_nx, in_dhx), mul(in_ny, in_dhy)), mul(in_nz, in_dhz))),
                     mul(konst(ONE_RAW / 2), in_c));
    if (MODE == 1 && !in_direct) r_now = in_first ? seed_r : seq_r;
    else r_now = seed_r;
    case (MODE)
      0: scale = div(konst(ONE_RAW), fx_sqrt(r_now));
      1: scale = fx_rsqrt(r_now);
      2: scale = rsqrt_newton(r_now, 0);
      3: scale = rsqrt_newton(r_now, 1);
      default: scale = rsqrt_newton(r_now, 2);
    endcase
  end

  // ---- timing: issue, the latency, hand-over ------------------------------------------
  // Held pixels in a ring: result, tag, and cycles until valid (`due`).
  fx_t held_x[CAPACITY], held_y[CAPACITY], held_z[CAPACITY];
  logic [TAG_W-1:0] held_tag[CAPACITY];
  logic [DUE_W-1:0] held_due[CAPACITY];
  logic [PTR_W-1:0] head, tail;
  logic [CNT_W-1:0] count;
  logic [DUE_W-1:0] busy;  // cycles until the next issue

  assign in_ready = busy == 0 && count < CNT_W'(CAPACITY);
  wire issue = in_valid && in_ready;
  wire hand_over = out_valid && out_ready;
  wire seeds = MODE == 1 && in_first;
  // Cycles from issue to valid, less one: II · (work − 1) + LATENCY − 1.
  wire [DUE_W-1:0] due_at_issue = DUE_W'((seeds ? II : 0) + LATENCY - 1);

  function automatic logic [PTR_W-1:0] next(input logic [PTR_W-1:0] p);
    return p == PTR_W'(CAPACITY - 1) ? 0 : p + 1;
  endfunction

  logic [PTR_W-1:0] head_next;
  logic [CNT_W-1:0] count_next;
  always_comb begin
    head_next = hand_over ? next(head) : head;
    count_next = count + CNT_W'(issue) - CNT_W'(hand_over);
  end

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
      for (int k = 0; k < CAPACITY; k++)
        if (held_due[k] != 0) held_due[k] <= held_due[k] - 1;
      busy <= busy != 0 ? busy - 1 : 0;
      if (issue) begin
        held_x[tail] <= mul(in_nx, scale);
        held_y[tail] <= mul(in_ny, scale);
        held_z[tail] <= mul(in_nz, scale);
        held_tag[tail] <= in_tag;
        held_due[tail] <= due_at_issue;
        tail <= next(tail);
        busy <= DUE_W'(II * (seeds ? 2 : 1) - 1);
        if (MODE == 1) begin  // R_{n+1} = R_n + δ_n, δ_{n+1} = δ_n + c
          seq_r <= add(r_now, in_first ? seed_delta : seq_delta);
          seq_delta <= add(in_first ? seed_delta : seq_delta, in_first ? in_c : seq_c);
          if (in_first) seq_c <= in_c;
        end
      end
      head <= head_next;
      count <= count_next;
      // Valid in the next cycle: the oldest pixel, once its cycles are done.
      out_valid <= count_next != 0 &&
                   (head_next == tail && issue ? due_at_issue == 0 : held_due[head_next] <= 1);
    end
  end

  assign out_tag = held_tag[head];
  assign out_nx = held_x[head];
  assign out_ny = held_y[head];
  assign out_nz = held_z[head];
endmodule
