// PNG images through libpng, the format's reference decoder (the io component). It
// verifies what the format promises, where stb_image does not: every chunk's CRC
// (ancillary chunks too: an error, not a warning), the size before anything is decoded,
// and — checked here — that every pixel of a paletted image indexes its palette.
#include <algorithm>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <memory>

#include <png.h>

#include "shadetlm/core/input_error.hpp"
#include "shadetlm/core/memory_budget.hpp"
#include "shadetlm/core/png_io.hpp"

namespace shadetlm::core {

namespace {

// What the decoder reports, in plain data: libpng's errors return by longjmp, which
// must not cross C++ objects with destructors.
struct Decode {
  char error[256] = "";
  png_uint_32 width = 0, height = 0;
  int bit_depth = 0, color_type = 0, palette_size = 0, bad_index = -1;
  png_color palette[256];
  png_byte palette_alpha[256];
  png_bytep* rows = nullptr;  // (here, not a local: a local set after setjmp is lost by longjmp)
};

extern "C" void on_png_error(png_structp png, png_const_charp message) {
  auto* d = static_cast<Decode*>(png_get_error_ptr(png));
  std::snprintf(d->error, sizeof d->error, "%s", message);
  png_longjmp(png, 1);
}
extern "C" void on_png_warning(png_structp, png_const_charp) {}

// Reads the header, then asks `room` for the pixels' buffer (nullptr: refused, the
// reason in d.error), then decodes into it: 8 or 16 bits a sample (as stored), RGBA,
// or one palette index a byte for a paletted image. False on any failure.
bool decode(std::FILE* file, Decode& d, unsigned char* (*room)(void* owner, Decode& d, size_t row_bytes),
            void* owner) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &d, on_png_error, on_png_warning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info) {
    std::snprintf(d.error, sizeof d.error, "out of memory");
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    std::free(d.rows);
    d.rows = nullptr;
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  png_init_io(png, file);
  png_set_crc_action(png, PNG_CRC_ERROR_QUIT, PNG_CRC_ERROR_QUIT);
  png_set_user_limits(png, 1u << 16, 1u << 16);  // (the size is judged by `room` too)
  png_read_info(png, info);
  png_get_IHDR(png, info, &d.width, &d.height, &d.bit_depth, &d.color_type, nullptr, nullptr, nullptr);
  const bool paletted = d.color_type == PNG_COLOR_TYPE_PALETTE;
  if (paletted) {
    png_colorp colours = nullptr;
    png_get_PLTE(png, info, &colours, &d.palette_size);
    std::memcpy(d.palette, colours, sizeof(png_color) * size_t(d.palette_size));
    std::memset(d.palette_alpha, 255, sizeof d.palette_alpha);
    png_bytep alpha = nullptr;
    int alphas = 0;
    if (png_get_tRNS(png, info, &alpha, &alphas, nullptr) & PNG_INFO_tRNS)
      std::memcpy(d.palette_alpha, alpha, size_t(std::min(alphas, 256)));
    png_set_packing(png);  // 1, 2 and 4-bit indices a byte each
  } else {
    png_set_expand_gray_1_2_4_to_8(png);
    if (png_get_valid(png, info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(png);
    if (!(d.color_type & PNG_COLOR_MASK_COLOR)) png_set_gray_to_rgb(png);
    if (!(d.color_type & PNG_COLOR_MASK_ALPHA) && !png_get_valid(png, info, PNG_INFO_tRNS))
      png_set_filler(png, d.bit_depth == 16 ? 0xffff : 0xff, PNG_FILLER_AFTER);
    if (d.bit_depth == 16) png_set_swap(png);  // samples in the machine's order
  }
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  const size_t row_bytes = png_get_rowbytes(png, info);
  unsigned char* pixels = room(owner, d, row_bytes);
  if (!pixels) png_longjmp(png, 1);
  d.rows = static_cast<png_bytep*>(std::malloc(sizeof(png_bytep) * d.height));
  if (!d.rows) png_error(png, "out of memory");
  for (png_uint_32 y = 0; y < d.height; ++y) d.rows[y] = pixels + row_bytes * y;
  png_read_image(png, d.rows);
  png_read_end(png, nullptr);  // the chunks after the pixels, their CRCs up to IEND
  std::free(d.rows);
  d.rows = nullptr;
  png_destroy_read_struct(&png, &info, nullptr);
  return true;
}

// An 8-bit sample in [0, 1], as its 16-bit widening v·257 over 65535 (as 16-bit samples
// are read, and as the texture reader always did).
float eight_bit(unsigned v) { return float(v * 257u) / 65535.0f; }

}  // namespace

Texture read_png(const std::string& path, uint64_t max_texels) {
  struct Owner {
    std::vector<unsigned char> pixels;
    uint64_t max_texels, file_bytes;
    bool refused = false;  // by its size
  } owner{{}, max_texels, 0};
  auto room = [](void* o, Decode& d, size_t row_bytes) -> unsigned char* {
    auto& own = *static_cast<Owner*>(o);
    if (uint64_t(d.width) * d.height > own.max_texels) {
      std::snprintf(d.error, sizeof d.error, "the image size %ux%u is more than %llu texels", unsigned(d.width),
                    unsigned(d.height), static_cast<unsigned long long>(own.max_texels));
      own.refused = true;
      return nullptr;
    }
    // Deflate packs at most 1032 bytes into one: a file that claims more rows than its
    // size can hold is refused before they are allocated.
    const int channels = d.color_type == PNG_COLOR_TYPE_RGB ? 3 : d.color_type == PNG_COLOR_TYPE_RGB_ALPHA ? 4
                         : d.color_type == PNG_COLOR_TYPE_GRAY_ALPHA ? 2 : 1;
    const uint64_t stored = ((uint64_t(d.width) * uint64_t(channels * d.bit_depth) + 7) / 8 + 1) * d.height;
    if (stored > own.file_bytes * 1032 + 4096) {
      std::snprintf(d.error, sizeof d.error, "the file (%llu bytes) is too small to hold the %ux%u image it claims",
                    static_cast<unsigned long long>(own.file_bytes), unsigned(d.width), unsigned(d.height));
      own.refused = true;
      return nullptr;
    }
    // The decoded rows and the float texels made of them.
    const std::string why = MemoryBudget::process().claim((row_bytes + kDecodedTexelBytes * d.width) * d.height);
    if (!why.empty()) {
      std::snprintf(d.error, sizeof d.error, "the image is %ux%u: %s", unsigned(d.width), unsigned(d.height),
                    why.c_str());
      own.refused = true;
      return nullptr;
    }
    try {
      own.pixels.resize(row_bytes * d.height);
    } catch (const std::bad_alloc&) {  // (no exception may leave through libpng's frames)
      std::snprintf(d.error, sizeof d.error, "out of memory for a %ux%u image", unsigned(d.width), unsigned(d.height));
      return nullptr;
    }
    return own.pixels.data();
  };
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), std::fclose);
  if (!file) throw InputError(path, "", "cannot open the image");
  std::fseek(file.get(), 0, SEEK_END);
  owner.file_bytes = uint64_t(std::max(0L, std::ftell(file.get())));
  std::rewind(file.get());
  Decode d;
  if (!decode(file.get(), d, room, &owner))
    throw InputError(path, "", (owner.refused ? std::string() : std::string("not a valid PNG: ")) + d.error);
  Texture t;
  t.width = int(d.width), t.height = int(d.height);
  t.texels.resize(size_t(d.width) * d.height);
  const unsigned char* p = owner.pixels.data();
  if (d.color_type == PNG_COLOR_TYPE_PALETTE) {
    for (size_t i = 0; i < t.texels.size(); ++i) {
      const int index = p[i];
      if (index >= d.palette_size)
        throw InputError(path, "", "pixel (" + std::to_string(i % d.width) + ", " + std::to_string(i / d.width) +
                                       ") indexes colour " + std::to_string(index) + " of a palette of " +
                                       std::to_string(d.palette_size));
      const png_color& c = d.palette[index];
      t.texels[i] = glm::vec4(eight_bit(c.red), eight_bit(c.green), eight_bit(c.blue), eight_bit(d.palette_alpha[index]));
    }
  } else if (d.bit_depth == 16) {
    const auto* s = reinterpret_cast<const uint16_t*>(p);
    for (size_t i = 0; i < t.texels.size(); ++i)
      for (int k = 0; k < 4; ++k) t.texels[i][k] = float(s[i * 4 + size_t(k)]) / 65535.0f;
  } else {
    for (size_t i = 0; i < t.texels.size(); ++i)
      for (int k = 0; k < 4; ++k) t.texels[i][k] = eight_bit(p[i * 4 + size_t(k)]);
  }
  return t;
}

}  // namespace shadetlm::core
