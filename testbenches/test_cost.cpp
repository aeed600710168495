// The silicon cost model (src/shadetlm/cost/, docs/silicon.md): the operators' power laws
// as docs/rtl.md prints them, the formats' operations built from them, a block's units
// from its operations and II, and a render's figures summed from its blocks'.
#include <cmath>
#include <fstream>
#include <regex>
#include <sstream>

#include "shadetlm/cost/operator_cost.hpp"
#include "shadetlm/cost/silicon.hpp"
#include "shadetlm/modules/pipeline/pipeline.hpp"
#include "test_util.hpp"

using namespace shadetlm;

namespace {
core::NumberFormat format(const std::string& name) { return core::NumberFormat::parse(name); }
}  // namespace

TEST_CASE("cost: the program's power laws are docs/rtl.md's, as scripts/operators.py --doc wrote both", "[cost]") {
  std::ifstream in(test::source_path("docs/rtl.md"));
  std::stringstream text;
  text << in.rdbuf();
  // | add | 138.9 · W^1.08 | 0.9979 | 0.3449 · W^1.15 | 0.9944 |
  const std::regex row(R"(\| (\w+) \| ([0-9.e+-]+) · W\^([0-9.]+) \| [0-9.]+ \| ([0-9.e+-]+) · W\^([0-9.]+) \|)");
  const std::string doc = text.str();
  int rows = 0;
  for (std::sregex_iterator m(doc.begin(), doc.end(), row), end; m != end; ++m, ++rows) {
    const std::string op = (*m)[1];
    INFO(op);
    // At W = 16 the doc's rounded coefficients (4 digits) and exponents (2 decimals: up to
    // 0.005 · ln 16 ≈ 1.4 % in W^k) give the program's figure within 2 %.
    const cost::OperatorCost c = cost::synthesized(op, 16);
    CHECK(std::stod((*m)[2]) * std::pow(16.0, std::stod((*m)[3])) == Approx(c.area_um2).epsilon(0.02));
    CHECK(std::stod((*m)[4]) * std::pow(16.0, std::stod((*m)[5])) == Approx(c.energy_pj).epsilon(0.02));
  }
  CHECK(rows == 9);
}

TEST_CASE("cost: each format's operations from the operators, growing with the word", "[cost]") {
  using cost::Operation;
  // Fixed point: the model's saturating sums and products, a 1/√ as a root and a division.
  const auto fx = *cost::operation_cost(Operation::Add, format("fixed:1.12"));
  CHECK(fx.area_um2 == Approx(cost::synthesized("add_sat", 14).area_um2));
  CHECK(cost::operation_cost(Operation::Mul, format("fixed:1.12"))->energy_pj ==
        Approx(cost::synthesized("mul_sat", 14).energy_pj));
  for (const char* f : {"fixed:1.12", "float16", "float32"}) {
    INFO(f);
    const auto sqrt = *cost::operation_cost(Operation::Sqrt, format(f)), div = *cost::operation_cost(Operation::Div, format(f));
    const auto rsqrt = *cost::operation_cost(Operation::Rsqrt, format(f));
    CHECK(rsqrt.area_um2 == Approx(sqrt.area_um2 + div.area_um2));
    CHECK(cost::operation_cost(Operation::Mul, format(f))->area_um2 > cost::operation_cost(Operation::Add, format(f))->area_um2);
  }
  for (Operation op : cost::kOperations) {
    INFO(cost::name_of(op));
    CHECK(cost::operation_cost(op, format("float32"))->area_um2 > cost::operation_cost(op, format("float16"))->area_um2);
    CHECK(cost::operation_cost(op, format("float32"))->energy_pj > cost::operation_cost(op, format("float16"))->energy_pj);
    double area = 0, energy = 0;
    for (int w = 4; w <= cost::kMaxPricedBits; ++w) {  // fixed:I.F of every word priced
      const auto c = *cost::operation_cost(op, core::NumberFormat::fixed(w / 2, w - 1 - w / 2));
      CHECK(c.area_um2 > area);
      CHECK(c.energy_pj > energy);
      area = c.area_um2, energy = c.energy_pj;
    }
    // Wider than the power laws are taken: no figure.
    CHECK(!cost::operation_cost(op, format("fixed:12.40")).has_value());
  }
}

TEST_CASE("cost: a block's units are its operations a cycle of its work, its energy every operation's", "[cost]") {
  const core::NumberFormat f32 = format("float32");
  modules::Ops ops;
  ops.add = 80, ops.mul = 60, ops.sqrt = 1, ops.lut = 7;  // in 30 cycles (10 items at II 3)
  const cost::BlockSilicon s = cost::block_silicon(ops, 30, f32, "pipeline.x.format");
  REQUIRE(s.priced);
  // 8 adds an item in 3 cycles: 3 adders; 6 products: 2 multipliers; a root for ten items: one.
  CHECK(s.units[0] == 3);
  CHECK(s.units[1] == 2);
  CHECK(s.units[2] == 0);
  CHECK(s.units[3] == 1);
  CHECK(s.unpriced_ops == 7);
  using cost::Operation;
  const auto add = *cost::operation_cost(Operation::Add, f32), mul = *cost::operation_cost(Operation::Mul, f32),
             sqrt = *cost::operation_cost(Operation::Sqrt, f32);
  CHECK(s.area_um2 == Approx(3 * add.area_um2 + 2 * mul.area_um2 + sqrt.area_um2));
  CHECK(s.energy_pj == Approx(80 * add.energy_pj + 60 * mul.energy_pj + sqrt.energy_pj));
  // An exact multiple needs no more: 60 products in 30 cycles are 2 units, in 10 six.
  ops = {};
  ops.mul = 60;
  CHECK(cost::block_silicon(ops, 30, f32, "").units[1] == 2);
  CHECK(cost::block_silicon(ops, 10, f32, "").units[1] == 6);
  const cost::BlockSilicon wide = cost::block_silicon(ops, 10, format("fixed:12.40"), "pipeline.x.format");
  CHECK(!wide.priced);
  CHECK(wide.why.find("pipeline.x.format") != std::string::npos);
  CHECK(wide.why.find("53-bit") != std::string::npos);
}

TEST_CASE("cost: a block that spends a cycle a light shares its units over them", "[cost][systemc]") {
  // Lighting takes a light a cycle (lighting_kernel.hpp): with two lights, a pixel's
  // products are done in two cycles, so it needs half as many multipliers (rounded up) as
  // one pixel's products.
  const core::Scene scene = core::load_scene(test::source_path("golden/demo/scene.json"), {});
  REQUIRE(scene.lights.size() == 2);
  const nlohmann::json j = modules::render_systemc(scene).stats_json();
  const nlohmann::json& l = j["blocks"]["lighting"];
  const double mul_a_pixel = l["ops"]["mul"].get<double>() / l["pixels"].get<double>();
  REQUIRE(mul_a_pixel > 2);
  CHECK(l["silicon"]["units"]["mul"].get<uint64_t>() == uint64_t(std::ceil(mul_a_pixel / 2 - 1e-9)));
}

TEST_CASE("cost: a render's silicon is its blocks', its power the energy over the simulated time",
          "[cost][systemc]") {
  const core::Scene scene = core::load_scene(test::source_path("golden/sphere/scene.json"), {});
  const nlohmann::json j = modules::render_systemc(scene).stats_json();
  const nlohmann::json& s = j["silicon"];
  double area = 0, energy = 0;
  for (const auto& [name, b] : j["blocks"].items()) {
    INFO(name);
    REQUIRE(b["silicon"]["priced"] == true);
    area += b["silicon"]["area_mm2"].get<double>(), energy += b["silicon"]["energy_nj"].get<double>();
  }
  CHECK(s["area_mm2"].get<double>() == Approx(area));
  CHECK(s["energy_nj"].get<double>() == Approx(energy));
  CHECK(area > 0);
  CHECK(s["energy_nj_per_shaded_pixel"].get<double>() == Approx(energy / j["pixels"]["shaded"].get<double>()));
  // mW: the frame's joules over its simulated seconds, times 1000.
  CHECK(s["power_mw"].get<double>() == Approx(energy * 1e-9 / j["sim_time_s"].get<double>() * 1e3));
  // The loop counts the same operations, so the same energy; it has no timing and counts
  // no block's pixels: no power, no units, no area.
  const nlohmann::json loop = modules::render_loop(scene).stats_json()["silicon"];
  CHECK(loop["energy_nj"].get<double>() == Approx(energy).epsilon(1e-12));
  CHECK(loop["area_mm2"].is_null());
  CHECK(loop["power_mw"].is_null());
  // Lighting reads its specular table: counted, not priced.
  CHECK(j["blocks"]["lighting"]["silicon"]["unpriced_ops"].get<uint64_t>() == j["blocks"]["lighting"]["ops"]["lut"].get<uint64_t>());
}

TEST_CASE("cost: a block whose format has no figure is named, and left out of the total", "[cost][systemc]") {
  const core::Scene scene = core::load_scene(test::source_path("golden/sphere/scene.json"),
                                             {"pipeline.normalize.format=fixed:12.40"});
  const nlohmann::json j = modules::render_systemc(scene).stats_json();
  const nlohmann::json& n = j["blocks"]["normalize"]["silicon"];
  CHECK(n["priced"] == false);
  CHECK(n["why"].get<std::string>().find("pipeline.normalize.format") != std::string::npos);
  CHECK(j["silicon"]["unpriced_blocks"] == nlohmann::json::array({"normalize"}));
  double area = 0;
  for (const auto& [name, b] : j["blocks"].items())
    if (b["silicon"]["priced"] == true) area += b["silicon"]["area_mm2"].get<double>();
  CHECK(j["silicon"]["area_mm2"].get<double>() == Approx(area));
}
