#pragma once
// A SystemC testbench for one span block: a driver thread sends packets to the block
// under test through a TLM-2.0 socket, a sink receives what it forwards and hands each
// packet to a check. Every SystemC report above info fails the test. SystemC
// elaborates once per process: one harness per test case (ctest runs each test case
// in a process of its own).
#include <functional>
#include <vector>

#include <systemc>
#include <tlm>
#include <tlm_utils/simple_initiator_socket.h>
#include <tlm_utils/simple_target_socket.h>

#include <catch2/catch.hpp>

#include "shadetlm/tlm/stage.hpp"

using namespace shadetlm;  // core::, modules::, reference::

namespace test {

inline void route_systemc_reports_to_failures() {
  sc_core::sc_report_handler::set_handler([](const sc_core::sc_report& r, const sc_core::sc_actions&) {
    if (r.get_severity() > sc_core::SC_INFO) FAIL("SystemC report: " << r.get_msg_type() << ": " << r.get_msg());
  });
}

struct Driver : sc_core::sc_module {
  tlm_utils::simple_initiator_socket<Driver> out;
  std::function<void(std::function<void(modules::SpanPacket&)>)> produce;  // calls send per packet
  // The delay annotation a packet is sent with (none: zero).
  std::function<sc_core::sc_time(const modules::SpanPacket&)> delay_of;
  SC_HAS_PROCESS(Driver);
  explicit Driver(sc_core::sc_module_name n) : sc_core::sc_module(n), out("out") { SC_THREAD(run); }
  void run() {
    tlm::tlm_generic_payload trans;
    trans.set_command(tlm::TLM_WRITE_COMMAND);
    produce([&](modules::SpanPacket& p) {
      trans.set_data_ptr(reinterpret_cast<unsigned char*>(&p));
      trans.set_data_length(sizeof p);
      sc_core::sc_time delay = delay_of ? delay_of(p) : sc_core::SC_ZERO_TIME;
      out->b_transport(trans, delay);
      REQUIRE(trans.get_response_status() == tlm::TLM_OK_RESPONSE);
    });
  }
};

struct Sink : sc_core::sc_module {
  tlm_utils::simple_target_socket<Sink> in;
  std::function<void(const modules::SpanPacket&)> check;
  std::function<void(const modules::SpanPacket&, const sc_core::sc_time&)> check_delay;  // optional
  uint64_t packets = 0;
  explicit Sink(sc_core::sc_module_name n) : sc_core::sc_module(n), in("in") {
    in.register_b_transport(this, &Sink::transport);
  }
  void transport(tlm::tlm_generic_payload& trans, sc_core::sc_time& delay) {
    ++packets;
    const auto& p = *reinterpret_cast<const modules::SpanPacket*>(trans.get_data_ptr());
    check(p);
    if (check_delay) check_delay(p, delay);
    trans.set_response_status(tlm::TLM_OK_RESPONSE);
  }
};

// Runs packets through Stage<Kernel>: driver → block → sink. Optionally, the delay each
// packet is sent with, and a check of the delay it reaches the sink with (a block passes
// it on unchanged: the pixels' times come from the pipeline's MainPassTiming).
template <class Kernel>
uint64_t run_stage(Kernel& kernel, std::function<void(std::function<void(modules::SpanPacket&)>)> produce,
                   std::function<void(const modules::SpanPacket&)> check,
                   std::function<sc_core::sc_time(const modules::SpanPacket&)> delay_of = {},
                   std::function<void(const modules::SpanPacket&, const sc_core::sc_time&)> check_delay = {},
                   modules::Timing timing = {}, sc_core::sc_time period = sc_core::sc_time(2, sc_core::SC_NS)) {
  route_systemc_reports_to_failures();
  Driver driver("driver");
  modules::Stage<Kernel> block("block", kernel, timing, period);
  Sink sink("sink");
  driver.produce = std::move(produce);
  driver.delay_of = std::move(delay_of);
  sink.check = std::move(check);
  sink.check_delay = std::move(check_delay);
  driver.out.bind(block.in);
  block.out.bind(sink.in);
  sc_core::sc_start();
  return sink.packets;
}

}  // namespace test
