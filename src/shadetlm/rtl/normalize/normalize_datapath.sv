// The normalize block's arithmetic for one pixel, in fixed:IBITS.FBITS: the modes and
// roundings are those of normalize_unit.sv (read its header). Combinational; synthesized
// alone, it is the datapath's cost apart from the timing's registers (scripts/synth.sh).
/* verilator lint_off WIDTH */
// One pixel's arithmetic. With `first` (forward-difference mode) the radicand is seeded
// from this normal, ΔN_H and c; after it from seq_r, which the unit keeps as next_r.
module normalize_datapath #(
    parameter integer IBITS = 3,
    parameter integer FBITS = 20,
    parameter integer MODE = 0
) (
    input  logic               first, direct,
    input  logic [IBITS+FBITS:0] nx, ny, nz, dhx, dhy, dhz, c,
    input  logic [IBITS+FBITS:0] seq_r, seq_delta, seq_c,
    output logic [IBITS+FBITS:0] out_x, out_y, out_z, next_r, next_delta
);
  localparam integer W = 1 + IBITS + FBITS;  // bits of a word
  localparam integer F = FBITS;
  // Holds every intermediate result, and a float32 significand shifted (from_float_bits).
  localparam integer WIDE = 2 * W + F + 4 > 48 ? 2 * W + F + 4 : 48;

  localparam [W-1:0] MAX = {1'b0, {(W - 1) {1'b1}}};
  localparam [W-1:0] MIN = {1'b1, {(W - 1) {1'b0}}};
  localparam [W-1:0] LSB = {{(W - 1) {1'b0}}, 1'b1};
  // The constants as the format holds them (saturated where it cannot).
  localparam [W-1:0] K_HALF = LSB << (F - 1);
  localparam [W-1:0] K_ONE = IBITS >= 1 ? LSB << F : MAX;
  localparam [W-1:0] K_THREE_HALVES = IBITS >= 1 ? (LSB << F) + (LSB << (F - 1)) : MAX;
  localparam [W-1:0] K_TWO = IBITS >= 2 ? LSB << (F + 1) : MAX;

  // ---- fixed-point operations ---------------------------------------------------------
  function automatic signed [W-1:0] sat(input signed [WIDE-1:0] x);
    reg signed [WIDE-1:0] hi, lo;
    begin
      hi = $signed(MAX);
      lo = $signed(MIN);
      sat = x > hi ? MAX : x < lo ? MIN : x[W-1:0];
    end
  endfunction
  function automatic signed [W-1:0] add(input signed [W-1:0] a, input signed [W-1:0] b);
    reg signed [WIDE-1:0] s;
    begin
      s = a;
      s = s + b;
      add = sat(s);
    end
  endfunction
  function automatic signed [W-1:0] sub(input signed [W-1:0] a, input signed [W-1:0] b);
    reg signed [WIDE-1:0] s;
    begin
      s = a;
      s = s - b;
      sub = sat(s);
    end
  endfunction
  function automatic signed [W-1:0] mul(input signed [W-1:0] a, input signed [W-1:0] b);
    reg signed [WIDE-1:0] p, bw, half;
    begin
      p = a;
      bw = b;
      half = {{(WIDE - 1) {1'b0}}, 1'b1} << (F - 1);
      p = (p * bw + half) >>> F;  // round half up
      mul = sat(p);
    end
  endfunction
  function automatic signed [W-1:0] div(input signed [W-1:0] a, input signed [W-1:0] b);
    reg signed [W+F:0] n, d, q, r, ar, ad;
    begin
      n = a;
      n = n <<< F;
      d = b;
      if (b == 0) begin
        div = a == 0 ? {W{1'b0}} : a[W-1] ? MIN : MAX;
      end else begin
        q = n / d;  // toward zero
        r = n % d;  // with the dividend's sign
        ar = r < 0 ? -r : r;
        ad = d < 0 ? -d : d;
        if ((ar <<< 1) >= ad) q = (n[W+F] == d[W+F]) ? q + 1 : q - 1;  // ties away from zero
        div = sat(q);
      end
    end
  endfunction

  // ---- the float32 estimate (a table in silicon) --------------------------------------
  // x·2^-F as float32 bits, rounded to nearest even.
  function automatic [31:0] to_float_bits(input signed [W-1:0] x);
    reg [W-1:0] m;
    reg [W+24:0] wide_m, rest;
    reg [24:0] mant;
    integer p, e, sh, i;
    begin
      m = x[W-1] ? -x : x;
      p = 0;
      for (i = 0; i < W; i = i + 1) if (m[i]) p = i;
      e = p - F + 127;
      wide_m = m;
      if (p <= 23) begin
        mant = wide_m << (23 - p);
      end else begin
        sh = p - 23;
        mant = wide_m >> sh;
        rest = wide_m & ((LSB << sh) - 1);  // the bits shifted out
        if (rest > (LSB << (sh - 1)) || (rest == (LSB << (sh - 1)) && mant[0])) mant = mant + 1;
        if (mant[24]) begin
          mant = mant >> 1;
          e = e + 1;
        end
      end
      to_float_bits = x == 0 ? 32'h0 : {x[W-1], e[7:0], mant[22:0]};
    end
  endfunction
  // Float32 bits to the format, rounded to nearest even; NaN gives 0, infinities saturate.
  function automatic signed [W-1:0] from_float_bits(input [31:0] b);
    reg [23:0] sig;
    reg signed [WIDE-1:0] v, low, half;
    integer k;
    begin
      sig = b[30:23] == 0 ? {1'b0, b[22:0]} : {1'b1, b[22:0]};
      k = (b[30:23] == 0 ? 1 : b[30:23]) - 150 + F;  // value·2^F = sig·2^k
      v = 0;
      if (k >= 0) begin
        v = sig;
        v = k > WIDE - 26 ? $signed(MAX) + 1 : v <<< k;  // past the format: saturates below
      end else if (-k <= 25) begin
        v = sig;
        v = v >>> (-k);
        low = sig & ((LSB << (-k)) - 1);
        half = LSB << (-k - 1);
        if (low > half || (low == half && v[0])) v = v + 1;
      end
      if (b[30:23] == 8'hff) from_float_bits = b[22:0] != 0 ? {W{1'b0}} : b[31] ? MIN : MAX;
      else from_float_bits = sat(b[31] ? -v : v);
    end
  endfunction
  function automatic signed [W-1:0] rsqrt_newton(input signed [W-1:0] r, input integer steps);
    reg signed [W-1:0] y, half_r;
    integer i;
    begin
      y = from_float_bits(32'h5f3759df - (to_float_bits(r) >> 1));
      half_r = mul(K_HALF, r);
      for (i = 0; i < steps; i = i + 1) y = mul(y, sub(K_THREE_HALVES, mul(mul(half_r, y), y)));
      rsqrt_newton = y;
    end
  endfunction
  function automatic signed [W-1:0] radicand(input signed [W-1:0] x, input signed [W-1:0] y,
                                               input signed [W-1:0] z);
    radicand = add(add(mul(x, x), mul(y, y)), mul(z, z));
  endfunction

  // ---- the radicand: direct, or by forward differences ---------------------------------
  logic signed [W-1:0] seed_r, seed_delta, r_now, scale, delta_now;
  always_comb begin
    seed_r = radicand(nx, ny, nz);
    seed_delta = add(mul(K_TWO, add(add(mul(nx, dhx), mul(ny, dhy)), mul(nz, dhz))), mul(K_HALF, c));
    r_now = MODE == 1 && !direct && !first ? seq_r : seed_r;
    delta_now = first ? seed_delta : seq_delta;
    // R_{n+1} = R_n + δ_n, δ_{n+1} = δ_n + c
    next_r = add(r_now, delta_now);
    next_delta = add(delta_now, first ? c : seq_c);
  end

  // ---- the inverse square root, by mode ------------------------------------------------
  generate
    if (MODE == 0) begin : g_exact
      // s = 1 / sqrt(r): the root of r·2^F in raw units, rounded up past s + ½.
      localparam integer N = (W + F + 1) / 2;
      logic [2*N-1:0] v;
      logic [N-1:0] root;
      logic [N+1:0] rem;
      logic signed [WIDE-1:0] rounded;
      assign v = r_now[W-1] ? 0 : {{(2 * N - W) {1'b0}}, r_now} << F;
      fx_isqrt #(.N(N)) isqrt (.v(v), .root(root), .rem(rem));
      always_comb begin
        rounded = root;
        if (rem > root) rounded = rounded + 1;
        scale = div(K_ONE, sat(rounded));
      end
    end else if (MODE == 1) begin : g_rsqrt_exact
      // s = √(2^3F / r): q, rq = 2^3F ÷ r, then rounded up past s + ½.
      localparam integer N = (3 * F + 2) / 2 > (W + 1) / 2 ? (3 * F + 2) / 2 : (W + 1) / 2;
      logic [2*N-1:0] q;
      logic [W-1:0] rq;
      logic [N-1:0] root;
      logic [N+1:0] rem;
      logic signed [WIDE-1:0] rounded;
      wire [2*N-1:0] num = {{(2 * N - 1) {1'b0}}, 1'b1} << (3 * F);
      wire [2*N-1:0] den = r_now[W-1] || r_now == 0 ? 1 : {{(2 * N - W) {1'b0}}, r_now};
      assign q = num / den;
      assign rq = num % den;
      fx_isqrt #(.N(N)) isqrt (.v(q), .root(root), .rem(rem));
      always_comb begin
        rounded = root;
        if (rem > root || (rem == root && {rq, 2'b00} > den)) rounded = rounded + 1;
        scale = r_now[W-1] || r_now == 0 ? MAX : sat(rounded);
      end
    end else begin : g_estimate
      assign scale = rsqrt_newton(r_now, MODE - 2);
    end
  endgenerate

  assign out_x = mul(nx, scale);
  assign out_y = mul(ny, scale);
  assign out_z = mul(nz, scale);
endmodule
/* verilator lint_on WIDTH */
