#include "shadetlm/core/texture.hpp"

#include <algorithm>
#include <cmath>
#include <memory>


#include "shadetlm/core/input_error.hpp"

namespace shadetlm::core {

namespace {
int wrap_index(int i, int n, Wrap w) {
  if (w == Wrap::Clamp) return std::clamp(i, 0, n - 1);
  int m = i % n;
  return m < 0 ? m + n : m;
}

Texture blank(const ProceduralParams& p, const char* name) {
  Texture t;
  t.name = name;
  t.width = p.size.x;
  t.height = p.size.y;
  t.texels.resize(size_t(t.width) * t.height);
  return t;
}

// Fills every texel from a function of the texel centre's (u, v) in [0,1]².
template <class F>
Texture generate(const ProceduralParams& p, const char* name, F f) {
  Texture t = blank(p, name);
  for (int y = 0; y < t.height; ++y)
    for (int x = 0; x < t.width; ++x) {
      glm::dvec2 uv((x + 0.5) / t.width, 1.0 - (y + 0.5) / t.height);
      t.texels[size_t(y) * t.width + x] = glm::vec4(f(uv), 1.0f);
    }
  return t;
}

glm::dvec3 mix3(glm::dvec3 a, glm::dvec3 b, double s) { return a + (b - a) * s; }

// A 32-bit integer hash (multiply / xor-shift rounds) for lattice values.
uint32_t hash(uint32_t x) {
  x ^= x >> 16; x *= 0x7feb352dU;
  x ^= x >> 15; x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}
uint32_t hash2(int x, int y, uint32_t seed) {
  return hash(uint32_t(x) * 0x9E3779B1U ^ hash(uint32_t(y) ^ hash(seed)));
}
double unit(uint32_t h) { return (h >> 8) * (1.0 / 16777216.0); }  // [0, 1)

double smooth(double t) { return t * t * t * (t * (t * 6 - 15) + 10); }  // C2 fade

// Lattice noises periodic with `period` cells along each axis.
double value_noise(glm::dvec2 q, glm::ivec2 period, uint32_t seed) {
  glm::dvec2 f = glm::floor(q), r = q - f;
  int x0 = int(f.x), y0 = int(f.y);
  auto v = [&](int dx, int dy) {
    return unit(hash2(wrap_index(x0 + dx, period.x, Wrap::Repeat),
                      wrap_index(y0 + dy, period.y, Wrap::Repeat), seed));
  };
  double sx = smooth(r.x), sy = smooth(r.y);
  double a = v(0, 0) + (v(1, 0) - v(0, 0)) * sx;
  double b = v(0, 1) + (v(1, 1) - v(0, 1)) * sx;
  return a + (b - a) * sy;
}

double gradient_noise(glm::dvec2 q, glm::ivec2 period, uint32_t seed) {  // about [-0.7, 0.7]
  glm::dvec2 f = glm::floor(q), r = q - f;
  int x0 = int(f.x), y0 = int(f.y);
  auto g = [&](int dx, int dy) {
    double angle = 6.283185307179586 *
                   unit(hash2(wrap_index(x0 + dx, period.x, Wrap::Repeat),
                              wrap_index(y0 + dy, period.y, Wrap::Repeat), seed));
    return std::cos(angle) * (r.x - dx) + std::sin(angle) * (r.y - dy);
  };
  double sx = smooth(r.x), sy = smooth(r.y);
  double a = g(0, 0) + (g(1, 0) - g(0, 0)) * sx;
  double b = g(0, 1) + (g(1, 1) - g(0, 1)) * sx;
  return a + (b - a) * sy;
}

// Sum of octaves, each twice the frequency and half the amplitude, normalized so that
// the result keeps the range of one octave.
template <class N>
double fractal(glm::dvec2 uv, const ProceduralParams& p, N noise) {
  double sum = 0, amplitude = 1, total = 0;
  glm::ivec2 period = p.cells;
  for (int o = 0; o < p.octaves; ++o) {
    sum += amplitude * noise(uv * glm::dvec2(period), period, p.seed + o);
    total += amplitude;
    amplitude *= 0.5;
    period *= 2;
  }
  return sum / total;
}
}  // namespace

glm::dvec4 Texture::texel(int x, int y) const {
  x = wrap_index(x, width, wrap);
  y = wrap_index(y, height, wrap);
  return glm::dvec4(texels[size_t(y) * width + x]);
}

glm::dvec4 Texture::bilinear(glm::dvec2 uv) const {
  double s = uv.x * width - 0.5, t = (1.0 - uv.y) * height - 0.5;
  // Bring far coordinates near the texture before converting to int: a whole number
  // of periods for repeat, one texel beyond the border for clamp (reads the same).
  if (wrap == Wrap::Repeat) {
    s -= width * std::floor(s / width);
    t -= height * std::floor(t / height);
  } else {
    s = std::clamp(s, -1.0, double(width));
    t = std::clamp(t, -1.0, double(height));
  }
  const double fs = std::floor(s), ft = std::floor(t);
  const int x = int(fs), y = int(ft);
  const double a = s - fs, b = t - ft;
  return (texel(x, y) * (1 - a) + texel(x + 1, y) * a) * (1 - b) +
         (texel(x, y + 1) * (1 - a) + texel(x + 1, y + 1) * a) * b;
}

double srgb_to_linear(double c) {
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}
double linear_to_srgb(double c) {
  return c <= 0.0031308 ? c * 12.92 : 1.055 * std::pow(c, 1 / 2.4) - 0.055;
}

uint32_t encode_unorm(float n, int bits) {
  return uint32_t(std::lround(std::clamp((n + 1.0f) * 0.5f, 0.0f, 1.0f) * float((1u << bits) - 1)));
}

Texture decode_unorm_normals(const Texture& t) {
  Texture d = t;
  d.srgb = false, d.unorm = false;
  for (auto& c : d.texels) c = glm::vec4(2.0f * glm::vec3(c) - 1.0f, c.a);
  for (auto& level : d.mips)
    for (auto& c : level.texels) c = glm::vec4(2.0f * glm::vec3(c) - 1.0f, c.a);
  return d;
}

bool NormalChannels::identity() const {
  for (int c = 0; c < 3; ++c)
    if (axis[c] != c || sign[c] != 1) return false;
  return true;
}

std::string NormalChannels::text() const {
  std::string out;
  for (int c = 0; c < 3; ++c) out += std::string(c ? "," : "") + (sign[c] < 0 ? "-" : "") + char('x' + axis[c]);
  return out;
}

Texture remap_normal_channels(const Texture& t, const NormalChannels& channels) {
  auto remap = [&](std::vector<glm::vec4>& texels) {
    for (auto& v : texels) {
      glm::vec4 n = v;
      for (int c = 0; c < 3; ++c) n[channels.axis[c]] = channels.sign[c] * v[c];
      v = n;
    }
  };
  Texture out = t;
  remap(out.texels);
  for (auto& level : out.mips) remap(level.texels);
  return out;
}

Texture decode_srgb(const Texture& t) {
  Texture out = t;
  for (auto& c : out.texels)
    for (int k = 0; k < 3; ++k) c[k] = float(srgb_to_linear(c[k]));
  out.srgb = false;
  return out;
}

Texture make_checker(const ProceduralParams& p) {
  return generate(p, "checker", [&](glm::dvec2 uv) {
    int cx = int(std::floor(uv.x * p.cells.x)), cy = int(std::floor(uv.y * p.cells.y));
    return ((cx + cy) & 1) ? p.color_b : p.color_a;
  });
}

Texture make_bricks(const ProceduralParams& p) {
  return generate(p, "bricks", [&](glm::dvec2 uv) {
    double y = uv.y * p.cells.y;
    int row = int(std::floor(y));
    double x = uv.x * p.cells.x + ((row & 1) ? 0.5 : 0.0);  // running bond
    double fx = x - std::floor(x), fy = y - row;
    bool mortar = fx < p.gap || fy < p.gap;
    return mortar ? p.color_b : p.color_a;
  });
}

Texture make_tiles(const ProceduralParams& p) {
  return generate(p, "tiles", [&](glm::dvec2 uv) {
    double x = uv.x * p.cells.x, y = uv.y * p.cells.y;
    int cx = int(std::floor(x)), cy = int(std::floor(y));
    double fx = x - cx, fy = y - cy;
    if (fx < p.gap || fy < p.gap) return p.color_b;
    double shade = 0.6 + 0.4 * unit(hash2(cx, cy, p.seed));
    return p.color_a * shade;
  });
}

Texture make_value_noise(const ProceduralParams& p) {
  return generate(p, "value-noise", [&](glm::dvec2 uv) {
    return mix3(p.color_b, p.color_a, fractal(uv, p, value_noise));
  });
}

Texture make_gradient_noise(const ProceduralParams& p) {
  return generate(p, "gradient-noise", [&](glm::dvec2 uv) {
    double n = std::clamp(0.5 + 0.7 * fractal(uv, p, gradient_noise), 0.0, 1.0);
    return mix3(p.color_b, p.color_a, n);
  });
}

Texture make_ridges(const ProceduralParams& p) {
  return generate(p, "ridges", [&](glm::dvec2 uv) {
    auto ridge = [](glm::dvec2 q, glm::ivec2 period, uint32_t seed) {
      return 1.0 - std::min(1.0, std::abs(gradient_noise(q, period, seed)) / 0.7);
    };
    return mix3(p.color_b, p.color_a, fractal(uv, p, ridge));
  });
}

Texture make_steps(const ProceduralParams& p) {
  return generate(p, "steps", [&](glm::dvec2 uv) {
    double n = fractal(uv, p, value_noise);
    double level = std::min(std::floor(n * p.levels), double(p.levels - 1));
    return mix3(p.color_b, p.color_a, p.levels > 1 ? level / (p.levels - 1) : 1.0);
  });
}

}  // namespace shadetlm::core
