// Testbench of lighting (bump-mapping paper, Fig. 1, "colour intensity"): packets of
// random unit normals, light and halfway vectors through the SystemC block, against
// Blinn-Phong computed here in double precision from the same inputs.
//
// Tolerance per channel, derived from float rounding (u = 2⁻²⁴): each dot product is
// off by at most 3u (|N| = |L| = 1); a product or sum adds u. The power x^s turns an
// input error e into a relative error of s·e/x, plus the power's own, 4u·(1 + |y|) with
// y = s·log2 x (specular_power, tested below). So a light contributes at most
// |k_d·tex|·(4u·N·L + 2u) + |k_s|·x^s·(s·4u/x + 4u·(1 + |y|) + 4u), the ambient term
// 2u·|ambient|, and the sum of the terms one u each.
#include <random>

#include "shadetlm/modules/lighting/lighting_kernel.hpp"
#include "shadetlm/modules/lighting/power.hpp"
#include "systemc_harness.hpp"

using namespace shadetlm;  // core::, modules::, reference::

TEST_CASE("specular_power: x^e within 4 float ulps times 1 + |e log2 x| of the exact power", "[lighting]") {
  // Every 997th float from the smallest subnormal to just past 1 (N·H exceeds 1 only by
  // rounding), for shininesses from below 1 to the largest a scene may set. The bound
  // is the error analysis of power.hpp: a few ulps from the series and the scaling, and
  // y = e·log2 x carried with a relative error of a few u, which exp turns into a
  // relative error of the result proportional to |y| (measured: at most 3.4).
  const double u = std::ldexp(1.0, -24);
  const float top = 1.0f + 8 * float(u);
  uint32_t last;
  std::memcpy(&last, &top, sizeof last);
  for (float e : {0.0f, 0.01f, 0.5f, 1.0f, 2.0f, 8.0f, 32.5f, 100.0f, 1000.0f, 1e6f}) {
    INFO("e = " << e);
    double worst = 0;  // error / (u·(1 + |y|)·x^e)
    float worst_x = 0;
    bool flushed = true;  // below float's normal range: 0, or within 2⁻¹²⁶
    for (uint32_t bits = 1; bits <= last; bits += 997) {
      float x;
      std::memcpy(&x, &bits, sizeof x);
      const double exact = std::pow(double(x), double(e));
      const double y = double(e) * std::log2(double(x));
      const double err = std::abs(double(modules::specular_power(x, e)) - exact);
      if (exact < 0x1p-126) {
        flushed = flushed && err <= 0x1p-126;
        continue;
      }
      const double ratio = err / (u * (1 + std::abs(y)) * exact);
      if (ratio > worst) worst = ratio, worst_x = x;
    }
    INFO("worst " << worst << " at x = " << worst_x);
    CHECK(worst <= 4);
    CHECK(flushed);
    if (e > 0) CHECK(worst > 0.1);  // the comparison saw rounding: it measures something
  }
  CHECK(modules::specular_power(1.0f, 1e6f) == 1.0f);
  CHECK(modules::specular_power(0.25f, 2.0f) == 0.0625f);
  CHECK(modules::specular_power(0x1p-140f, 0.5f) == 0x1p-70f);  // a subnormal x
  CHECK(modules::specular_power(0.5f, 200.0f) == 0.0f);         // 2⁻²⁰⁰: under the range
}

TEST_CASE("lighting: Blinn-Phong of every light, against double precision", "[lighting][systemc]") {
  const double u = std::ldexp(1.0, -24);
  core::Scene scene;
  scene.camera.local_viewer = true;  // H varies per pixel for every light
  scene.ambient = {0.1, 0.05, 0.2};
  core::Light sun, lamp, spot;
  sun.direction = glm::normalize(glm::dvec3(-1, -2, -1));
  sun.color = {1, 0.9, 0.8};
  lamp.type = spot.type = core::Light::Type::Point;
  lamp.intensity = 2;
  spot.color = {0.2, 0.4, 1};
  scene.lights = {sun, lamp, spot};
  std::vector<core::Material> materials(3);
  materials[0].shininess = 1;
  materials[1].shininess = 40;
  materials[2].shininess = 200;
  materials[2].texture = 0;  // textured: the packet's tex modulates ambient and diffuse
  modules::LightingKernel kernel(scene);

  std::mt19937 rng(13);
  std::normal_distribution<float> g;
  std::uniform_real_distribution<float> unit(0, 1);
  auto random_unit = [&](float v[3]) {
    const glm::dvec3 d = glm::normalize(glm::dvec3(g(rng), g(rng), g(rng)));
    for (int c = 0; c < 3; ++c) v[c] = float(d[c]);
  };
  modules::TriangleSetup tri;
  modules::SpanPacket packet{};  // zeroed: kernels may compute the lanes past a count (kLanes)
  double worst_ratio = 0;
  uint64_t lit = 0, highlights = 0;

  auto produce = [&](std::function<void(modules::SpanPacket&)> send) {
    for (int k = 0; k < 300; ++k) {
      core::Material& m = materials[k % 3];
      for (int c = 0; c < 3; ++c) m.ambient[c] = unit(rng), m.diffuse[c] = unit(rng), m.specular[c] = unit(rng);
      tri.material = &m;
      packet.tri = &tri;
      packet.count = 1 + k % modules::kSpanMax;
      for (int i = 0; i < packet.count; ++i) {
        float n[3], v[3];
        random_unit(n);
        random_unit(v);  // a viewer direction, to build H from
        for (int c = 0; c < 3; ++c) packet.n[c][i] = n[c], packet.tex[c][i] = unit(rng);
        for (int li = 0; li < 3; ++li) {
          float l[3];
          if (li == 0) {
            for (int c = 0; c < 3; ++c) l[c] = float(-sun.direction[c]);
          } else {
            random_unit(l);
            // Half of the point-light directions near N: highlights get exercised.
            if (i % 2) for (int c = 0; c < 3; ++c) l[c] = n[c] + 0.2f * l[c];
          }
          glm::dvec3 L(l[0], l[1], l[2]);
          L = glm::normalize(L);
          const glm::dvec3 H = glm::normalize(L + glm::dvec3(v[0], v[1], v[2]));
          for (int c = 0; c < 3; ++c) packet.l[li][c][i] = float(L[c]), packet.h[li][c][i] = float(H[c]);
        }
      }
      send(packet);
    }
  };
  auto check = [&](const modules::SpanPacket& p) {
    const core::Material& m = *p.tri->material;
    const bool textured = m.texture >= 0;
    for (int i = 0; i < p.count; ++i) {
      const glm::dvec3 N(p.n[0][i], p.n[1][i], p.n[2][i]);
      const glm::dvec3 tex = textured ? glm::dvec3(p.tex[0][i], p.tex[1][i], p.tex[2][i]) : glm::dvec3(1);
      glm::dvec3 want = scene.ambient * m.ambient * tex, bound = 2 * u * want;
      for (int li = 0; li < 3; ++li) {
        const glm::dvec3 L(p.l[li][0][i], p.l[li][1][i], p.l[li][2][i]);
        const glm::dvec3 H(p.h[li][0][i], p.h[li][1][i], p.h[li][2][i]);
        const glm::dvec3 rad = scene.lights[li].radiance();
        const double nl = glm::dot(N, L), nh = glm::dot(N, H);
        const double d = std::max(nl, 0.0);
        const double s = nl > 0 && nh > 0 ? std::pow(nh, m.shininess) : 0.0;
        lit += nl > 0;
        highlights += s > 0.5;
        want += rad * (m.diffuse * tex * d + m.specular * s);
        bound += rad * m.diffuse * tex * (4 * u * d + 2 * u) +
                 rad * m.specular * s *
                     (s > 0 ? m.shininess * 4 * u / nh + 4 * u * (1 + m.shininess * std::abs(std::log2(nh))) + 4 * u : 0.0);
        // At N·L ≈ 0 or N·H ≈ 0 the float select may land on the other side: allow
        // the term it switches.
        if (std::abs(nl) < 4 * u) bound += rad * (m.diffuse * tex * std::abs(nl) + m.specular * (nh > 0 ? std::pow(nh, m.shininess) : 0.0));
      }
      for (int c = 0; c < 3; ++c) {
        const double err = std::abs(double(p.rgb[c][i]) - want[c]);
        const double b = bound[c] + 4 * u * want[c] + 1e-30;
        REQUIRE(err <= b);
        worst_ratio = std::max(worst_ratio, err / b);
      }
    }
  };
  CHECK(test::run_stage(kernel, produce, check) == 300);
  INFO("worst error / bound " << worst_ratio << ", lit " << lit << ", highlights " << highlights);
  CHECK(worst_ratio > 0);
  CHECK(lit > 1000);
  CHECK(highlights > 100);
  // Operations: the declared datapath, 1 table look-up (the power) per pixel and light.
  uint64_t pixels = 0, textured_pixels = 0;
  for (int k = 0; k < 300; ++k) pixels += 1 + k % modules::kSpanMax, textured_pixels += k % 3 == 2 ? 1 + k % modules::kSpanMax : 0;
  CHECK(kernel.ops().lut == 3 * pixels);
  CHECK(kernel.ops().mul == kernel.ops_per_pixel(false).mul * (pixels - textured_pixels) +
                                kernel.ops_per_pixel(true).mul * textured_pixels + kernel.ops_per_span().mul * 300);
}
