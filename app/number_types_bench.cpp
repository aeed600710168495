// number_types_bench: the fixed-point type of the datapaths (modules::Fixed) against
// SystemC's sc_fix_fast, the library's fastest fixed-point type whose widths are set
// at run time (as a block's format is), with the same rounding and saturation
// (SC_RND, SC_SAT). The work: the walker's and lighting's arithmetic, a chain of
// multiply-adds over arrays (a·b + c, rounded and saturated each operation), in one
// run each (these machines are noisy; scripts/bench.sh prints the ratio). Also float
// and Half, for scale. Usage: number_types_bench [I F]
#define SC_INCLUDE_FX
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include <systemc>

#include "shadetlm/numeric/number.hpp"

using namespace shadetlm;  // core::, modules::, reference::

namespace {

constexpr int kValues = 4096, kRounds = 200;

template <class T>
double seconds_per_op(const std::vector<double>& input, double& checksum) {
  std::vector<T> a(input.begin(), input.end()), b(kValues), c(kValues);
  for (int i = 0; i < kValues; ++i) b[size_t(i)] = T(input[size_t((i * 7) % kValues)] * 0.5), c[size_t(i)] = T(0.25);
  const auto start = std::chrono::steady_clock::now();
  for (int r = 0; r < kRounds; ++r)
    for (int i = 0; i < kValues; ++i) c[size_t(i)] = a[size_t(i)] * b[size_t(i)] + c[size_t(i)] * T(0.5);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (const T& v : c) checksum += double(v);
  return s / (3.0 * kValues * kRounds);  // a mul, a mul, an add
}

}  // namespace

int sc_main(int argc, char** argv) {
  const int int_bits = argc > 2 ? std::atoi(argv[1]) : 3, frac_bits = argc > 2 ? std::atoi(argv[2]) : 20;
  const core::NumberFormat format = core::NumberFormat::fixed(int_bits, frac_bits);
  std::vector<double> input(kValues);
  for (int i = 0; i < kValues; ++i) input[size_t(i)] = std::ldexp(double((i * 2654435761u) % 65536) - 32768, -14);
  double sums[4] = {0, 0, 0, 0};
  const double f32 = seconds_per_op<float>(input, sums[0]);
  modules::NumberContext half_context(core::NumberFormat::parse("float16"));
  double f16;
  {
    modules::NumberScope scope(half_context);
    f16 = seconds_per_op<modules::Half>(input, sums[1]);
  }
  modules::NumberContext fixed_context(format);
  double own;
  {
    modules::NumberScope scope(fixed_context);
    own = seconds_per_op<modules::Fixed>(input, sums[2]);
  }
  // sc_fix_fast with the same format: word length 1 + I + F, I + 1 integer bits with the sign.
  const sc_dt::sc_fxtype_params params(1 + int_bits + frac_bits, 1 + int_bits, sc_dt::SC_RND, sc_dt::SC_SAT);
  const sc_dt::sc_fxtype_context context(params);
  const double systemc = seconds_per_op<sc_dt::sc_fix_fast>(input, sums[3]);
  std::printf("number types, ns per operation (multiply-add chains, %s):\n", format.name().c_str());
  std::printf("  float32            %8.2f\n  float16 (Half)     %8.2f\n", f32 * 1e9, f16 * 1e9);
  std::printf("  fixed (Fixed)      %8.2f\n  sc_fix_fast        %8.2f\n", own * 1e9, systemc * 1e9);
  std::printf("  sc_fix_fast / Fixed: %.2f   (checksums %.6g %.6g)\n", systemc / own, sums[2], sums[3]);
  return 0;
}
