// The number types of the datapaths (numeric/number.hpp) and the per-block
// formats of the pipeline (docs/numerical-stability.md): float16 rounding checked against
// the compiler's own binary16, fixed point's grid, rounding and saturation, the events
// counted, and the formats at work in whole frames.
#include <cmath>
#include <cstring>
#include <random>
#include <set>

#include "shadetlm/core/compare.hpp"
#include "shadetlm/numeric/number.hpp"
#include "shadetlm/modules/parallax/parallax_kernel.hpp"
#include "shadetlm/modules/pipeline/pipeline.hpp"
#include "test_util.hpp"

using namespace shadetlm;  // core::, modules::, reference::

using modules::Fixed;
using modules::Half;
using modules::NumberContext;
using modules::NumberScope;

namespace {

// The value of binary16 bit pattern `bits`, decoded by hand from the IEEE layout.
double half_value(uint16_t bits) {
  const int sign = bits >> 15, exponent = (bits >> 10) & 0x1f, mantissa = bits & 0x3ff;
  const double magnitude = exponent == 0    ? std::ldexp(mantissa, -24)
                           : exponent == 31 ? (mantissa ? NAN : HUGE_VAL)
                                            : std::ldexp(1024 + mantissa, exponent - 25);
  return sign ? -magnitude : magnitude;
}

double rgb_difference(const core::Frame& a, const core::Frame& b) {
  core::CompareOptions o;
  o.layers = {"RGB"};
  return core::compare_frames(a, b, o).layers.at(0).max_abs;
}

}  // namespace

TEST_CASE("float16: every binary16 value is kept and every midpoint rounds to even", "[numbers]") {
  for (uint32_t bits = 0; bits < 0x7c00; ++bits) {  // the finite non-negative values
    const double v = half_value(uint16_t(bits));
    REQUIRE(modules::round_to_half(v) == v);
    REQUIRE(modules::round_to_half(-v) == -v);
    if (bits + 1 == 0x7c00) break;
    const double next = half_value(uint16_t(bits + 1)), mid = (v + next) / 2;  // exact in double
    const double even = (bits & 1) ? next : v;
    INFO("between " << v << " and " << next);
    REQUIRE(modules::round_to_half(mid) == even);
    REQUIRE(modules::round_to_half(std::nextafter(mid, 0.0)) == v);
    REQUIRE(modules::round_to_half(std::nextafter(mid, HUGE_VAL)) == next);
  }
  // Past the largest finite value (65504), from the midpoint to 65536 on: infinity.
  CHECK(modules::round_to_half(65519.99) == 65504.0);
  CHECK(std::isinf(modules::round_to_half(65520.0)));
  CHECK(modules::round_to_half(0x1p-25) == 0.0);                 // half the smallest subnormal: to even (0)
  CHECK(modules::round_to_half(0x1.8p-25) == 0x1p-24);           // over half of it: the smallest subnormal
#ifdef __FLT16_MANT_DIG__
  // The compiler's own conversion, where it has one, on random floats of every binade.
  std::mt19937 rng(7);
  for (int i = 0; i < 200000; ++i) {
    uint32_t fbits = rng() & 0x47ffffffu;  // |x| < 2^17, both signs
    float x;
    std::memcpy(&x, &fbits, sizeof x);
    REQUIRE(modules::round_to_half(double(x)) == double(float(_Float16(x))));
  }
#endif
}

TEST_CASE("float16 arithmetic rounds each result once and counts overflows and invalid operations", "[numbers]") {
  NumberContext context(core::NumberFormat::parse("float16"));
  NumberScope scope(context);
  const Half a = 1.0f, tiny = 0x1p-11f;  // tiny: half an ulp of 1
  CHECK(float(a + tiny) == 1.0f);         // a tie: to even
  CHECK(float(a + tiny + tiny) == 1.0f);  // rounded after each addition, not once at the end
  CHECK(float(Half(2049.0f)) == 2048.0f); // 11 significant bits
  CHECK(context.events.overflows == 0);
  const Half big = 60000.0f;
  CHECK(std::isinf(float(big + big)));
  CHECK(context.events.overflows == 1);
  CHECK(std::isnan(float(modules::sqrt_op(Half(-1.0f)))));
  CHECK(context.events.invalid == 1);
  const Half inf = big + big;
  (void)(inf - inf);  // NaN from an infinity: counted (the operands are not NaN)
  CHECK(context.events.invalid == 2);
  CHECK(context.events.overflows == 2);  // big + big once more
  CHECK(std::isinf(float(a / Half(0.0f))));  // infinite already before rounding: an overflow too
  CHECK(std::isinf(float(modules::rsqrt_op(Half(0.0f)))));
  CHECK(context.events.overflows == 4);
}

TEST_CASE("float16 parallax tracer on rays that overflow it: the entry kept, never a non-finite uv", "[numbers]") {
  // Rays a few 10^-7 off the surface step ~10^5 texels a layer: past float16's 65504.
  core::Texture steps;
  steps.width = steps.height = 16;
  steps.texels.resize(256);
  for (int i = 0; i < 256; ++i) steps.texels[size_t(i)] = glm::vec4(((i % 16) / 4 + (i / 64)) % 2 ? 1.0f : 0.0f);
  NumberContext half(core::NumberFormat::parse("float16"));
  int kept = 0;
  for (auto [method, cones] : {std::pair{core::ParallaxMethod::Relief, core::ConeKind::Classic},
                               {core::ParallaxMethod::Pom, core::ConeKind::Classic},
                               {core::ParallaxMethod::Cone, core::ConeKind::Classic},
                               {core::ParallaxMethod::Cone, core::ConeKind::Relaxed},
                               {core::ParallaxMethod::Distance, core::ConeKind::Classic}}) {
    core::ParallaxSettings s;
    s.method = method, s.cones = cones;
    s.depth = 0.1;
    s.layers_max = 64;
    const modules::ParallaxMaps maps = modules::build_parallax_maps(steps, s, "steps");
    for (float c : {-1.5e-7f, -5e-7f, -1e-4f, -0.5f}) {
      INFO(int(method) << " " << core::to_string(cones) << " c " << c);
      const uint64_t overflows = half.events.overflows;
      const modules::ParallaxTrace t = modules::trace_parallax(s, maps, 3.3f, 5.1f, 0.7f, 0.3f, c, nullptr, &half);
      CHECK(std::isfinite(t.x));
      CHECK(std::isfinite(t.y));
      if (half.events.overflows > overflows) {  // this ray overflowed: its entry is kept
        CHECK(t.x == 3.3f);
        CHECK(t.y == 5.1f);
        ++kept;
      }
    }
  }
  CHECK(kept > 0);  // the grazing layered rays do overflow float16
}

TEST_CASE("fixed point: the grid, rounding, saturation and the events counted", "[numbers]") {
  NumberContext context(core::NumberFormat::parse("fixed:3.4"));  // k/16 in [−8, 8 − 1/16]
  NumberScope scope(context);
  CHECK(double(Fixed(0.03125)) == 0.0);     // a tie to even: 0.5 LSB → 0
  CHECK(double(Fixed(0.09375)) == 0.125);   // 1.5 LSB → 2 LSB
  CHECK(double(Fixed(-0.7)) == -0.6875);
  CHECK(double(Fixed(7.9375)) == 7.9375);
  CHECK(context.events.overflows == 0);
  CHECK(double(Fixed(9.0)) == 7.9375);      // saturated
  CHECK(double(Fixed(-1e300)) == -8.0);
  CHECK(double(Fixed(HUGE_VAL)) == 7.9375);
  CHECK(context.events.overflows == 3);
  CHECK(double(Fixed(4.0) + Fixed(4.0)) == 7.9375);
  CHECK(double(-Fixed(-8.0)) == 7.9375);
  CHECK(context.events.overflows == 5);
  // Products: exact, then rounded once (half up) to the grid.
  CHECK(double(Fixed(0.0625) * Fixed(0.5)) == 0.0625);    // 0.03125: half an LSB, up
  CHECK(double(Fixed(-0.0625) * Fixed(0.5)) == 0.0);      // −0.03125: half an LSB, up (to 0)
  CHECK(double(Fixed(1.5) * Fixed(-2.25)) == -3.375);
  // Quotients round to nearest; a division by zero saturates and is counted.
  CHECK(double(Fixed(1.0) / Fixed(3.0)) == 0.3125);        // 5.33 LSB → 5
  CHECK(double(Fixed(-1.0) / Fixed(3.0)) == -0.3125);
  CHECK(double(Fixed(0.0625) / Fixed(2.0)) == 0.0625);     // half an LSB: away from zero
  CHECK(double(Fixed(-0.0625) / Fixed(2.0)) == -0.0625);
  CHECK(double(Fixed(1.0) / Fixed(0.0)) == 7.9375);
  CHECK(double(Fixed(-1.0) / Fixed(0.0)) == -8.0);
  CHECK(context.events.invalid == 2);
  CHECK(double(modules::sqrt_op(Fixed(2.0))) == 1.4375);   // 1.41421… → 22.6 LSB → 23
  CHECK(double(modules::rsqrt_op(Fixed(0.25))) == 2.0);
  CHECK(double(modules::floor_op(Fixed(-0.5))) == -1.0);
  CHECK(double(modules::floor_op(Fixed(2.9375))) == 2.0);
  CHECK(double(Fixed(std::nan(""))) == 0.0);
  CHECK(context.events.invalid == 3);
  // The widest format keeps 52 bits: exact for every float32 of its range.
  NumberContext wide(core::NumberFormat::parse("fixed:4.48"));
  NumberScope wide_scope(wide);
  CHECK(double(Fixed(0x1.fffffep-1f)) == double(0x1.fffffep-1f));
  CHECK(double(Fixed(3.0) * Fixed(5.0)) == 15.0);
  CHECK(wide.events.overflows == 0);
}

TEST_CASE("number format names: parsed, printed, and bad ones refused naming the field", "[numbers]") {
  CHECK(core::NumberFormat::parse("float32").name() == "float32");
  CHECK(core::NumberFormat::parse("float16").name() == "float16");
  CHECK(core::NumberFormat::parse("fixed:0.15").name() == "fixed:0.15");
  CHECK(core::NumberFormat::parse("fixed:30.22").name() == "fixed:30.22");
  for (const char* bad : {"float64", "fixed", "fixed:3", "fixed:3.", "fixed:3.4x", "fixed:-1.4", "fixed:+3.4",
                          "fixed:3. 4", "fixed:31.4", "fixed:3.0", "fixed:3.49", "fixed:10.43", "Fixed:3.4",
                          "fixed:3.\t4", "fixed:\n3.4", "fixed:4294967196.48", "fixed:99999999999999999999.4",
                          "fixed:0x3.4", "fixed:.4", "fixed:3.4.5"}) {
    INFO(bad);
    CHECK_THROWS_AS(core::NumberFormat::parse(bad), std::invalid_argument);
  }
  const char* scene = R"({"camera": {"position": [0, 0, 5], "target": [0, 0, 0], "resolution": [64, 48]},
                          "objects": [{"shape": "sphere"}]})";
  CHECK(std::string(test::scene_error(scene, {"pipeline.normalize.format=fixed:3.60"}).what())
            .find("pipeline.normalize.format") != std::string::npos);
  CHECK(std::string(test::scene_error(scene, {"pipeline.number_format=default"}).what())
            .find("pipeline.number_format") != std::string::npos);
  const core::Scene s =
      core::load_scene_text(scene, "ok.json", ".", {"pipeline.number_format=float16", "pipeline.lighting.format=fixed:2.14"});
  const core::Settings settings = test::settings(s);
  const auto pipeline = core::read<modules::PipelineSettings>(settings, "");
  auto format_of = [&](const std::string& block) {  // as the block's BlockContext resolves it
    modules::BlockBasics formatted;
    formatted.formatted = true;
    const modules::BlockBasics basics = core::read(settings, block + ".", formatted);
    return modules::BlockContext{s, settings, block, pipeline, basics}.format().name();
  };
  CHECK(format_of("normalize") == "float16");  // default: number_format
  CHECK(format_of("lighting") == "fixed:2.14");
}

TEST_CASE("a wide fixed-point format runs the same algorithms as float32, a narrow one shows its error", "[numbers]") {
  // Every formatted block these scenes elaborate at once (all but parallax, which
  // test_parallax and the float16 tracer test cover), on the demo (Phong, point light,
  // local viewer) and a texture-object scene. fixed:12.40 keeps more bits than float32 over these ranges:
  // the frame must match float32's to a few float32 ulps of colour; float16 must not.
  for (const std::string file : {"scenes/demo.json", "golden/texture-object/scene.json"}) {
    INFO(file);
    const core::Scene base = core::load_scene(test::source_path(file));
    const core::Frame f32 = modules::render_loop(base).frame;
    auto render = [&](const std::string& format) {
      return modules::render_loop(core::load_scene(test::source_path(file), {"pipeline.number_format=" + format}));
    };
    const modules::RenderResult wide = render("fixed:12.40"), half = render("float16");
    const double wide_error = rgb_difference(wide.frame, f32), half_error = rgb_difference(half.frame, f32);
    INFO("fixed:12.40 " << wide_error << ", float16 " << half_error);
    CHECK(wide_error < 1e-5);
    CHECK(half_error > 1e-4);  // 11 significant bits show
    CHECK(half_error < 0.1);
    const auto stats = wide.stats_json();
    CHECK(stats["numbers"]["overflows"] == 0);
    CHECK(stats["blocks"]["lighting"]["numbers"]["format"] == "fixed:12.40");
  }
}

TEST_CASE("fixed-point overflow saturates the colour and is counted in the block that overflowed", "[numbers]") {
  // fixed:0.16 holds [−1, 1): the demo's brightest colours saturate in lighting; the
  // blocks before it, in a wide fixed format, count nothing.
  const core::Scene s = core::load_scene(test::source_path("scenes/demo.json"),
                                         {"pipeline.number_format=fixed:12.30", "pipeline.lighting.format=fixed:0.16"});
  const modules::RenderResult r = modules::render_loop(s);
  const auto stats = r.stats_json();
  CHECK(stats["blocks"]["lighting"]["numbers"]["overflows"].get<uint64_t>() > 0);
  for (const char* block : {"normal_interp", "normalize", "vector_interp"}) {
    INFO(block);
    CHECK(stats["blocks"][block]["numbers"]["format"] == "fixed:12.30");
    CHECK(stats["blocks"][block]["numbers"]["overflows"] == 0);
  }
  float brightest = 0;
  for (const char* c : {"R", "G", "B"})
    for (float v : r.frame.find(c)->values) brightest = std::max(brightest, v);
  CHECK(brightest <= 1.0f - 0x1p-16f);
}

TEST_CASE("float16 lighting under a light past its range: counted, and no infinity reaches the frame, specular composite included",
          "[numbers]") {
  // Radiance 10^6 overflows float16 (65504) in the diffuse and specular factors; on the
  // texture-object path the specular term is composited after the frame (texel_project).
  const core::Scene s = core::load_scene(test::source_path("golden/texture-object/scene.json"),
                                         {"lights.0.intensity=1e6", "pipeline.lighting.format=float16"});
  const modules::RenderResult r = modules::render_loop(s);
  const auto stats = r.stats_json();
  CHECK(stats["blocks"]["lighting"]["numbers"]["overflows"].get<uint64_t>() > 0);
  CHECK(stats["blocks"]["lighting"]["numbers"]["nonfinite"].get<uint64_t>() > 0);
  CHECK(stats["nonfinite_replaced"].get<uint64_t>() > 0);
  for (const auto& c : r.frame.channels)
    if (c.name != "Z")
      for (float v : c.values) REQUIRE(std::isfinite(v));
}

// Each kernel declares its operation counts (ops in the stats); here the float32
// datapaths run on Counted<float> instead, which counts what the code does, and the two
// are held together per block. Checked: the blocks whose datapath is written over the
// number type. The texture unit's filters (texture_fetch, bump_fetch) are held to their
// declared counts in test_texturing, the parallax tracers' in test_parallax (all but
// the exact cell test, float32 in core, and the block's per-pixel entry and exit, by
// hand). Not checked: texel_project (its per-triangle setup in double), and setup,
// raster, framebuffer (no number format).
TEST_CASE("every formatted block's declared operation counts are what its number type counts", "[numbers][ops]") {
  struct Case {
    const char* scene;
    std::vector<std::string> sets;
  };
  const std::vector<Case> cases = {
      {"golden/sphere/scene.json", {}},
      {"golden/point-light/scene.json", {}},
      {"golden/point-light/scene.json", {"pipeline.normalize.mode=forward-difference", "pipeline.normalize.seed=line"}},
      {"golden/point-light/scene.json", {"pipeline.normalize.mode=rsqrt1", "pipeline.vector_interp.h=interpolated"}},
      {"golden/demo/scene.json", {}},
      {"golden/bump-plane/scene.json", {}},
      {"golden/bump-sphere/scene.json", {}},
      {"golden/bump-object/scene.json", {}},
      {"golden/texture-object/scene.json", {}},
      {"golden/parallax-steps/scene.json", {}},
  };
  modules::count_float32_operations = true;
  for (const auto& c : cases) {
    const core::Scene scene = core::load_scene(test::source_path(c.scene), c.sets);
    const modules::RenderResult r = modules::render_loop(scene);
    for (const auto& b : r.blocks) {
      static const std::set<std::string> checked = {"normal_interp", "normalize", "vector_interp", "bump_perturb",
                                                    "lighting"};
      if (!checked.count(b.name)) continue;
      REQUIRE(b.numbers);
      const modules::Ops& d = b.stats.ops;
      const modules::Ops& k = b.numbers->events.counted;
      INFO(c.scene << " [" << (c.sets.empty() ? "" : c.sets.back()) << "] " << b.name << " pixels "
                   << b.stats.pixels << " packets " << b.stats.packets << " " << test::arithmetic_diff(d, k));
      CHECK(test::same_arithmetic(d, k));
    }
  }
  modules::count_float32_operations = false;
}
