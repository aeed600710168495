#include "shadetlm/rtl/normalize/normalize_unit_pins.hpp"

#include <stdexcept>
#include <type_traits>

#include <verilated_vcd_sc.h>

#include "shadetlm/rtl/normalize_rtl_build.hpp"

namespace shadetlm::rtl {

namespace {

// The verilated model V with its inputs driven by the reference's unit. The pixel data
// are zeros: the unit's timing does not depend on them (only on in_first).
template <class V>
class NormalizeUnitPins : public sc_core::sc_module, public timing_reference::UnitPins {
  template <class Port> using data_of = typename std::remove_reference_t<Port>::data_type;
  using Word = data_of<decltype(std::declval<V&>().in_nx)>;
  using Tag = data_of<decltype(std::declval<V&>().in_tag)>;

 public:
  SC_HAS_PROCESS(NormalizeUnitPins);
  NormalizeUnitPins(sc_core::sc_module_name name, const std::string& vcd)
      : sc_core::sc_module(name), vcd_(vcd), model_((std::string(name) + "_rtl").c_str()) {
    model_.rst(rst_), model_.in_valid(in_valid_), model_.in_ready(in_ready_), model_.in_first(in_first_);
    model_.in_direct(zero_bit_), model_.in_tag(in_tag_), model_.out_tag(out_tag_);
    model_.in_nx(zero_[0]), model_.in_ny(zero_[1]), model_.in_nz(zero_[2]);
    model_.in_dhx(zero_[3]), model_.in_dhy(zero_[4]), model_.in_dhz(zero_[5]), model_.in_c(zero_[6]);
    model_.out_nx(out_[0]), model_.out_ny(out_[1]), model_.out_nz(out_[2]);
    rst_.write(true);  // reset at the first edge
    SC_METHOD(copy_item);
    sensitive << out_tag_;
    dont_initialize();
  }
  ~NormalizeUnitPins() override {
    if (trace_) trace_->close();
  }
  void bind(sc_core::sc_signal_in_if<bool>& clk, sc_core::sc_signal<bool>& out_valid,
            sc_core::sc_signal<bool>& out_ready, sc_core::sc_signal<int64_t>& out_item) override {
    model_.clk(clk), model_.out_valid(out_valid), model_.out_ready(out_ready);
    item_ = &out_item;
  }
  void offer(bool valid, int64_t item, bool first) override {
    rst_.write(false);
    in_valid_.write(valid), in_tag_.write(Tag(item)), in_first_.write(first);
  }
  bool in_ready() const override { return in_ready_.read(); }

 private:
  void copy_item() { item_->write(int64_t(out_tag_.read())); }
  void start_of_simulation() override {
    if (vcd_.empty()) return;
    trace_ = std::make_unique<VerilatedVcdSc>();
    model_.trace(trace_.get(), 99);
    trace_->open(vcd_.c_str());
  }

  std::string vcd_;
  V model_;
  sc_core::sc_signal<bool> rst_, in_valid_, in_ready_, in_first_, zero_bit_;
  sc_core::sc_signal<Tag> in_tag_, out_tag_;
  sc_core::sc_signal<Word> zero_[7], out_[3];
  sc_core::sc_signal<int64_t>* item_ = nullptr;
  std::unique_ptr<VerilatedVcdSc> trace_;
};

}  // namespace

std::unique_ptr<timing_reference::UnitPins> make_normalize_unit_pins(int mode, const std::string& vcd) {
  if (!vcd.empty()) Verilated::traceEverOn(true);
  switch (mode) {
    case 0: return std::make_unique<NormalizeUnitPins<Vnormalize_exact>>("normalize_pins", vcd);
    case 1: return std::make_unique<NormalizeUnitPins<Vnormalize_forward_difference>>("normalize_pins", vcd);
    case 2: return std::make_unique<NormalizeUnitPins<Vnormalize_rsqrt0>>("normalize_pins", vcd);
    case 3: return std::make_unique<NormalizeUnitPins<Vnormalize_rsqrt1>>("normalize_pins", vcd);
    case 4: return std::make_unique<NormalizeUnitPins<Vnormalize_rsqrt2>>("normalize_pins", vcd);
    default: throw std::invalid_argument("no RTL normalize unit of mode " + std::to_string(mode));
  }
}

UnitTiming normalize_unit_timing(int mode) {
  if (mode < 0 || mode > 4) throw std::invalid_argument("no RTL normalize unit of mode " + std::to_string(mode));
  return {kNormalizeTiming[mode].latency, kNormalizeTiming[mode].ii};
}

}  // namespace shadetlm::rtl
