// A testbench of normalize_unit on test vectors (docs/rtl.md, "Test vectors"): reads
// normalize.in.hex and normalize.out.hex (`shadetlm render --vectors`), offers every
// pixel to the unit in order as fast as it takes them, and compares each output word
// with the vector's. Prints "normalize_tb: N pixels, M different" and stops with $fatal
// when any differs or the unit stops putting out. Built and run by scripts/rtl-vectors.sh
// (Verilator's --binary, the unit's parameters from the vectors' header), as:
//   Vnormalize_tb +in=normalize.in.hex +out=normalize.out.hex +pixels=N
/* verilator lint_off WIDTH */
module normalize_tb;
  parameter integer IBITS = 3, FBITS = 20, MODE = 0, LATENCY = 40, II = 3, MAX_PIXELS = 1 << 20;
  localparam integer W = 1 + IBITS + FBITS;
  localparam integer IN_BITS = 2 + 7 * W, OUT_BITS = 3 * W;

  logic [IN_BITS-1:0] vin[MAX_PIXELS];
  logic [OUT_BITS-1:0] vout[MAX_PIXELS];
  integer pixels, sent, received, different, cycles;
  string in_file, out_file;

  logic clk = 0, rst = 1;
  logic in_valid, in_ready, out_valid;
  logic [IN_BITS-1:0] offered;
  logic [W-1:0] out_nx, out_ny, out_nz;
  logic [31:0] out_tag;

  normalize_unit #(.IBITS(IBITS), .FBITS(FBITS), .MODE(MODE), .LATENCY(LATENCY), .II(II)) unit (
      .clk(clk), .rst(rst), .in_valid(in_valid), .in_ready(in_ready),
      .in_first(offered[IN_BITS-1]), .in_direct(offered[IN_BITS-2]), .in_tag(sent),
      .in_nx(offered[6*W+:W]), .in_ny(offered[5*W+:W]), .in_nz(offered[4*W+:W]),
      .in_dhx(offered[3*W+:W]), .in_dhy(offered[2*W+:W]), .in_dhz(offered[W+:W]), .in_c(offered[0+:W]),
      .out_valid(out_valid), .out_ready(1'b1), .out_tag(out_tag),
      .out_nx(out_nx), .out_ny(out_ny), .out_nz(out_nz));

  initial begin
    if (!$value$plusargs("in=%s", in_file) || !$value$plusargs("out=%s", out_file) ||
        !$value$plusargs("pixels=%d", pixels))
      $fatal(1, "normalize_tb: give +in=FILE +out=FILE +pixels=N");
    if (pixels < 1 || pixels > MAX_PIXELS) $fatal(1, "normalize_tb: +pixels must be in 1 … %0d", MAX_PIXELS);
    $readmemh(in_file, vin, 0, pixels - 1);
    $readmemh(out_file, vout, 0, pixels - 1);
  end

  always #5 clk <= ~clk;
  assign in_valid = !rst && sent < pixels;
  assign offered = sent < pixels ? vin[sent] : 0;

  initial begin
    sent = 0;
    received = 0;
    different = 0;
    cycles = 0;
  end
  always @(posedge clk) rst <= 0;  // reset for the first cycle

  always @(posedge clk) begin
    if (!rst) begin
      cycles <= cycles + 1;
      if (in_valid && in_ready) sent <= sent + 1;
      if (out_valid) begin
        if (out_tag != received) $fatal(1, "normalize_tb: pixel %0d came out where %0d was due", out_tag, received);
        if ({out_nx, out_ny, out_nz} !== vout[received]) begin
          if (different < 5)
            $display("normalize_tb: pixel %0d: RTL %h, vector %h", received, {out_nx, out_ny, out_nz}, vout[received]);
          different <= different + 1;
        end
        received <= received + 1;
      end
      if (received == pixels) begin
        $display("normalize_tb: %0d pixels, %0d different, %0d cycles", pixels, different, cycles);
        if (different != 0) $fatal(1, "normalize_tb: outputs differ from the vectors");
        $finish;
      end
      if (cycles > (pixels + 2) * (2 * II + LATENCY) + 100) $fatal(1, "normalize_tb: the unit stopped putting out");
    end
  end
endmodule
/* verilator lint_on WIDTH */
