// Textures from image files (the io component): PNG through libpng, JPEG through stb, EXR.
#include <algorithm>
#include <cmath>
#include <memory>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfTiledInputFile.h>
#include <stb_image.h>

#include "shadetlm/core/input_error.hpp"
#include "shadetlm/core/input_file.hpp"
#include "shadetlm/core/memory_budget.hpp"
#include "shadetlm/core/png_io.hpp"
#include "shadetlm/core/texture.hpp"

namespace shadetlm::core {

namespace {
constexpr uint64_t kMaxTexels = uint64_t(1) << 28;  // an image's, of any format (4 GiB as float RGBA)

// The channels R, G, B, A (or Y as grey) of an EXR as float texels: channels that are
// missing read 0 (A: 1). A tiled, mip-mapped file gives its levels 1 … in `mips`.
Texture read_exr_texture(const std::string& path) {
  Texture t;
  Imf::InputFile in(path.c_str());
  const Imf::Header& header = in.header();
  const Imath::Box2i dw = header.dataWindow();
  // A grey image (Y, no R) is read into R and copied to G and B: a frame buffer holds
  // one slice per channel name.
  const bool grey = header.channels().findChannel("Y") && !header.channels().findChannel("R");
  if (!grey && !header.channels().findChannel("R") && !header.channels().findChannel("G") &&
      !header.channels().findChannel("B"))
    throw std::runtime_error("the image has no colour channel (R, G, B or Y)");
  const char* names[4] = {grey ? "Y" : "R", "G", "B", "A"};
  auto read_level = [&](auto& file, int width, int height, Imath::Box2i window, auto read) {
    Texture l;
    l.width = width, l.height = height;
    if (width <= 0 || height <= 0 || uint64_t(width) * uint64_t(height) > kMaxTexels)
      throw std::runtime_error("the image size " + std::to_string(width) + "×" + std::to_string(height) +
                               " is out of range");
    const std::string why = MemoryBudget::process().claim(uint64_t(width) * uint64_t(height) * kDecodedTexelBytes);
    if (!why.empty()) throw std::runtime_error("the image is " + std::to_string(width) + "x" + std::to_string(height) + ": " + why);
    l.texels.assign(size_t(width) * height, glm::vec4(0, 0, 0, 1));
    Imf::FrameBuffer fb;
    char* origin = reinterpret_cast<char*>(l.texels.data()) -
                   (ptrdiff_t(window.min.x) + ptrdiff_t(window.min.y) * width) * ptrdiff_t(sizeof(glm::vec4));
    for (int c = 0; c < 4; ++c) {
      if (grey && (c == 1 || c == 2)) continue;
      fb.insert(names[c], Imf::Slice(Imf::FLOAT, origin + c * sizeof(float), sizeof(glm::vec4),
                                     sizeof(glm::vec4) * size_t(width), 1, 1, c == 3 ? 1.0 : 0.0));
    }
    file.setFrameBuffer(fb);
    read(file);
    if (grey)
      for (auto& t : l.texels) t.g = t.b = t.r;
    return l;
  };
  t = read_level(in, dw.max.x - dw.min.x + 1, dw.max.y - dw.min.y + 1, dw,
                 [&](Imf::InputFile& f) { f.readPixels(dw.min.y, dw.max.y); });
  if (header.hasTileDescription() && header.tileDescription().mode == Imf::MIPMAP_LEVELS) {
    Imf::TiledInputFile tiled(path.c_str());
    for (int l = 1; l < tiled.numLevels(); ++l) {
      const Imath::Box2i lw = tiled.dataWindowForLevel(l);
      t.mips.push_back(read_level(tiled, tiled.levelWidth(l), tiled.levelHeight(l), lw, [&](Imf::TiledInputFile& f) {
        f.readTiles(0, f.numXTiles(l) - 1, 0, f.numYTiles(l) - 1, l);
      }));
    }
  }
  return t;
}

}  // namespace

Texture load_texture_file(const std::string& path) {
  check_input_file(path, "", kMaxImageBytes);
  Texture t;
  t.name = path;
  auto ends_with = [&](const char* ext) {
    std::string e = ext, s = path;
    if (s.size() < e.size()) return false;
    std::transform(s.begin(), s.end(), s.begin(), ::tolower);
    return s.compare(s.size() - e.size(), e.size(), e) == 0;
  };
  if (ends_with(".exr")) {
    try {
      t = read_exr_texture(path);
    } catch (const std::exception& e) {
      throw InputError(path, "", std::string("cannot read the EXR image: ") + e.what());
    }
  } else if (ends_with(".png")) {
    t = read_png(path, kMaxTexels);
    t.srgb = t.unorm = true;  // 8- and 16-bit images hold display-encoded colours
  } else if (ends_with(".jpg") || ends_with(".jpeg")) {
    int channels = 0;
    if (!stbi_info(path.c_str(), &t.width, &t.height, &channels))
      throw InputError(path, "", std::string("cannot read the image: ") + stbi_failure_reason());
    if (uint64_t(t.width) * uint64_t(t.height) > kMaxTexels)
      throw InputError(path, "", "the image size " + std::to_string(t.width) + "x" + std::to_string(t.height) +
                                     " is more than " + std::to_string(kMaxTexels) + " texels");
    MemoryBudget::process().take(uint64_t(t.width) * uint64_t(t.height) * (kDecodedTexelBytes + 8), path, "");
    std::unique_ptr<stbi_us, void (*)(void*)> data(
        stbi_load_16(path.c_str(), &t.width, &t.height, &channels, 4), stbi_image_free);
    if (!data)
      throw InputError(path, "", std::string("cannot read the image: ") + stbi_failure_reason());
    t.texels.resize(size_t(t.width) * t.height);
    for (size_t i = 0; i < t.texels.size(); ++i)
      for (int k = 0; k < 4; ++k) t.texels[i][k] = data.get()[i * 4 + k] / 65535.0f;
    t.srgb = t.unorm = true;  // 8- and 16-bit images hold display-encoded colours
  } else {
    throw InputError(path, "", "unknown image type (use .png, .jpg or .exr)");
  }
  t.name = path;
  if (t.width <= 0 || t.height <= 0) throw InputError(path, "", "the image is empty");
  // Texels within ±1e6 (NaN and infinity refused): products with colours and lights stay
  // finite in float32 (docs/scene-format.md).
  auto bounded = [](const glm::vec4& c) {
    return std::abs(c.r) <= 1e6f && std::abs(c.g) <= 1e6f && std::abs(c.b) <= 1e6f && std::abs(c.a) <= 1e6f;
  };
  for (const auto& c : t.texels)
    if (!bounded(c)) throw InputError(path, "", "the image holds NaN, infinite or larger than 1e6 values");
  for (const auto& level : t.mips)
    for (const auto& c : level.texels)
      if (!bounded(c)) throw InputError(path, "", "a mip level holds NaN, infinite or larger than 1e6 values");
  return t;
}

}  // namespace shadetlm::core
