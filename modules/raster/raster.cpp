#include "shadetlm/modules/raster/raster.hpp"

namespace shadetlm::modules {

Raster::Raster(sc_core::sc_module_name name, RasterKernel& kernel, Timing timing, sc_core::sc_time period)
    : sc_core::sc_module(name), in("in"), out("out"), kernel_(kernel), schedule_(timing), period_(period) {
  in.register_b_transport(this, &Raster::b_transport);
  span_.set_command(tlm::TLM_WRITE_COMMAND);
}

BlockStats Raster::stats() const {
  BlockStats s = stats_;
  s.ops = kernel_.ops();
  s.busy_cycles = schedule_.busy_cycles();
  return s;
}

void Raster::b_transport(tlm::tlm_generic_payload& trans, sc_core::sc_time& delay) {
  if (is_pass_end(trans)) {
    pass_end(*reinterpret_cast<PassEnd*>(trans.get_data_ptr()));
    return out->b_transport(trans, delay);
  }
  const TriangleSetup& t = *reinterpret_cast<const TriangleSetup*>(trans.get_data_ptr());
  const sc_core::sc_time now = sc_core::sc_time_stamp();  // the same for every packet of the triangle
  const uint64_t arrival = uint64_t((now + delay) / period_ + 0.5);
  const uint64_t walked_before = kernel_.pixels_walked();
  const uint64_t start = std::max(arrival, schedule_.free_cycle());
  kernel_.run(t, [&](SpanPacket& p) {
    // It leaves `latency` after the walk has passed its last pixel.
    const uint64_t walked = kernel_.row_walked_before() - walked_before + uint64_t(p.x0 + p.count - p.row_start);
    p.cycle = start + schedule_.timing().ii * walked + schedule_.timing().latency;
    ++stats_.packets;
    stats_.pixels += uint64_t(p.count);
    if (kTracing && tracer_ && tracer_->region().covers(p.y, p.x0, p.x0 + p.count, t.id))
      for (int i = 0; i < p.count; ++i)
        if (tracer_->region().contains(p.x0 + i, p.y)) {
          const double values[2] = {p.inv_w[i], p.w[i]};
          // Pixel i leaves II per pixel walked after the packet's first.
          tracer_->record(probe_, p.cycle - schedule_.timing().ii * uint64_t(p.count - 1 - i), p.x0 + i, p.y,
                          t.id, values);
        }
    span_.set_data_ptr(reinterpret_cast<unsigned char*>(&p));
    span_.set_data_length(sizeof(SpanPacket));
    span_.set_address(uint64_t(p.y) << 32 | uint32_t(p.x0));
    forward(out, span_, p.cycle, period_, now);
  });
  schedule_.occupy(arrival, kernel_.pixels_walked() - walked_before);
  // Setup and raster work per triangle: their tracks keep the triangles of the filter.
  if (kTracing && timeline_ && triangle_kept(t.id))
    timeline_->add(track_, schedule_.last_start(), schedule_.last_busy(),
                   uint32_t(kernel_.pixels_walked() - walked_before), t.id);
  trans.set_response_status(tlm::TLM_OK_RESPONSE);
}

}  // namespace shadetlm::modules
