// Testbench of the RTL normalize unit (docs/rtl.md) against the fixed-point kernel, word
// for word, on the values the golden scenes never reach: normals past the format's
// range (saturating squares and sums), zero, tiny and non-finite normals, radicand
// sequences that run negative, large ΔN_H and c, bump packets (forward-difference
// mode's direct radicand) — 1500 packets of 1 to 64 pixels a mode. The transactor also
// checks every pixel's pin timing. Skipped (a warning) where the build has no RTL.
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <sstream>

#include "shadetlm/modules/normalize/normalize_kernel.hpp"
#include "shadetlm/modules/normalize/normalize_rtl.hpp"
#include "systemc_harness.hpp"

using modules::NormalizeMode;

namespace {

// The format and the mode's timing this build's RTL has ("fixed:3.20; exact latency 40 II 3; …").
struct Built {
  core::NumberFormat format;
  modules::Timing timing;
};
Built built(NormalizeMode mode) {
  std::istringstream s(modules::normalize_rtl_build());
  std::string format, name, word;
  std::getline(s, format, ';');
  Built b{core::NumberFormat::parse(format), {}};
  while (s >> name >> word >> b.timing.latency >> word >> b.timing.ii) {
    if (name == modules::normalize_mode_names()[size_t(mode)]) return b;
    s.ignore(1);  // ';'
  }
  FAIL("no timing for mode " << int(mode) << " in " << modules::normalize_rtl_build());
  return b;
}

// A component: mostly of order one, often past the format's range, sometimes zero,
// tiny or not finite.
float hostile(std::mt19937& rng, float range) {
  std::uniform_real_distribution<float> u(-1, 1);
  switch (rng() % 16) {
    case 0: return 0.0f;
    case 1: return u(rng) * 1e-5f;
    case 2: return u(rng) * 4 * range;  // saturates
    case 3: return rng() % 2 ? range : -range;
    case 4: return rng() % 8 ? u(rng) * range : std::numeric_limits<float>::quiet_NaN();
    case 5: return rng() % 2 ? std::numeric_limits<float>::infinity() : -std::numeric_limits<float>::infinity();
    default: return u(rng);
  }
}

struct Packets : sc_core::sc_module {
  SC_HAS_PROCESS(Packets);
  // (The RTL's model is a module: made while elaborating.)
  Packets(sc_core::sc_module_name n, NormalizeMode mode)
      : sc_core::sc_module(n), mode_(mode), built_(built(mode)), kernel_(mode, built_.format),
        rtl_(mode, built_.format, built_.timing, "test") {
    SC_THREAD(run);
  }
  uint64_t pixels = 0, differing = 0;
  modules::NumberEvents events() const { return kernel_.numbers().events; }
  std::string first_difference;

 private:
  void run() {
    const float range = std::ldexp(1.0f, built_.format.int_bits);  // the format's magnitude
    std::mt19937 rng(17 + unsigned(mode_));
    core::Material bump;
    bump.path = core::ShadingPath::BumpTangent;
    for (int packet = 0; packet < 1500; ++packet) {
      modules::TriangleSetup t;
      t.material = packet % 5 == 0 ? &bump : &modules::kDefaultMaterial;
      for (auto& plane : t.n) plane.ax = hostile(rng, range) * (packet % 3 == 0 ? 1.0f : 0.01f);
      t.c = packet % 7 == 0 ? hostile(rng, range) : 2 * (t.n[0].ax * t.n[0].ax + t.n[1].ax * t.n[1].ax + t.n[2].ax * t.n[2].ax);
      modules::SpanPacket a;
      a.tri = &t, a.count = 1 + int(rng() % 64), a.x0 = packet, a.y = 0;
      for (int i = 0; i < a.count; ++i)
        for (int k = 0; k < 3; ++k)  // a span that steps by ΔN_H, then perturbed now and then
          a.n[k][i] = (i == 0 || rng() % 8 == 0) ? hostile(rng, range) : a.n[k][i - 1] + t.n[k].ax;
      modules::SpanPacket r = a;
      kernel_.process(a);
      rtl_.process(r);
      for (int i = 0; i < a.count; ++i) {
        ++pixels;
        if (std::memcmp(&a.n[0][i], &r.n[0][i], sizeof(float)) == 0 &&
            std::memcmp(&a.n[1][i], &r.n[1][i], sizeof(float)) == 0 &&
            std::memcmp(&a.n[2][i], &r.n[2][i], sizeof(float)) == 0)
          continue;
        if (differing++ == 0) {
          std::ostringstream s;
          s << "packet " << packet << " pixel " << i << ": kernel (" << a.n[0][i] << ", " << a.n[1][i] << ", "
            << a.n[2][i] << "), RTL (" << r.n[0][i] << ", " << r.n[1][i] << ", " << r.n[2][i] << ")";
          first_difference = s.str();
        }
      }
    }
  }
  NormalizeMode mode_;
  Built built_;
  modules::NormalizeKernel kernel_;
  modules::NormalizeRtlKernel rtl_;
};

void check_mode(NormalizeMode mode) {
  if (!modules::normalize_rtl_built()) {
    WARN("skipped: " << modules::normalize_rtl_build());
    return;
  }
  test::route_systemc_reports_to_failures();
  Packets packets("packets", mode);
  sc_core::sc_start();
  INFO(packets.first_difference);
  CHECK(packets.pixels > 30000);
  CHECK(packets.differing == 0);
  CHECK(packets.events().overflows > 0);  // the hostile values saturated the kernel's format
  CHECK(packets.events().invalid > 0);    // and gave it NaN inputs or roots of negatives
}

}  // namespace

TEST_CASE("RTL normalize exact mode: every word the kernel's on hostile values", "[rtl]") {
  check_mode(NormalizeMode::Exact);
}
TEST_CASE("RTL normalize forward-difference mode: every word the kernel's on hostile values", "[rtl]") {
  check_mode(NormalizeMode::ForwardDifference);
}
TEST_CASE("RTL normalize rsqrt0 mode: every word the kernel's on hostile values", "[rtl]") {
  check_mode(NormalizeMode::Rsqrt0);
}
TEST_CASE("RTL normalize rsqrt1 mode: every word the kernel's on hostile values", "[rtl]") {
  check_mode(NormalizeMode::Rsqrt1);
}
TEST_CASE("RTL normalize rsqrt2 mode: every word the kernel's on hostile values", "[rtl]") {
  check_mode(NormalizeMode::Rsqrt2);
}
