// Your own SystemC testbench around one shadetlm block: the normalize block, in its
// fast-inverse-square-root mode with one Newton step, fed span packets by a driver
// thread and drained by a sink. Build it against an installed shadetlm (docs/reuse.md).
#include <cmath>
#include <cstdio>

#include <systemc>
#include <tlm_utils/simple_initiator_socket.h>
#include <tlm_utils/simple_target_socket.h>

#include "shadetlm/tlm/stage.hpp"
#include "shadetlm/modules/normalize/normalize_kernel.hpp"

struct Driver : sc_core::sc_module {
  tlm_utils::simple_initiator_socket<Driver> out{"out"};
  shadetlm::modules::TriangleSetup triangle;  // the packet's triangle: its ΔN_H and c
  shadetlm::modules::SpanPacket packet{};
  SC_CTOR(Driver) { SC_THREAD(run); }
  void run() {
    packet.tri = &triangle;
    packet.count = shadetlm::modules::kSpanMax;
    for (int i = 0; i < packet.count; ++i) {  // normals of every length and direction
      packet.n[0][i] = 0.1f * float(i) - 3.0f;
      packet.n[1][i] = 2.0f;
      packet.n[2][i] = 0.5f + 0.01f * float(i);
    }
    tlm::tlm_generic_payload trans;
    trans.set_command(tlm::TLM_WRITE_COMMAND);
    trans.set_data_ptr(reinterpret_cast<unsigned char*>(&packet));
    trans.set_data_length(sizeof packet);
    sc_core::sc_time delay = sc_core::SC_ZERO_TIME;
    out->b_transport(trans, delay);
  }
};

struct Sink : sc_core::sc_module {
  tlm_utils::simple_target_socket<Sink> in{"in"};
  double worst = 0;
  int pixels = 0;
  SC_CTOR(Sink) { in.register_b_transport(this, &Sink::transport); }
  void transport(tlm::tlm_generic_payload& trans, sc_core::sc_time&) {
    const auto& p = *reinterpret_cast<const shadetlm::modules::SpanPacket*>(trans.get_data_ptr());
    for (int i = 0; i < p.count; ++i, ++pixels) {
      const double len = std::sqrt(double(p.n[0][i]) * p.n[0][i] + double(p.n[1][i]) * p.n[1][i] +
                                   double(p.n[2][i]) * p.n[2][i]);
      worst = std::max(worst, std::abs(len - 1.0));
    }
    trans.set_response_status(tlm::TLM_OK_RESPONSE);
  }
};

int sc_main(int, char*[]) {
  shadetlm::modules::NormalizeKernel kernel(shadetlm::modules::NormalizeMode::Rsqrt1);
  Driver driver("driver");
  shadetlm::modules::Stage<shadetlm::modules::NormalizeKernel> normalize("normalize", kernel, shadetlm::modules::Timing{12, 1},
                                                     sc_core::sc_time(2, sc_core::SC_NS));
  Sink sink("sink");
  driver.out.bind(normalize.in);
  normalize.out.bind(sink.in);
  sc_core::sc_start();
  const shadetlm::modules::BlockStats s = normalize.stats();
  std::printf("normalize (rsqrt1): %d pixels, worst |length - 1| = %.3g, %llu busy cycles, %llu multiplications\n",
              sink.pixels, sink.worst, (unsigned long long)s.busy_cycles, (unsigned long long)s.ops.mul);
  // One Newton step leaves at most 0.18 % (docs/pipeline.md).
  return sink.pixels == shadetlm::modules::kSpanMax && sink.worst < 0.0018 ? 0 : 1;
}
