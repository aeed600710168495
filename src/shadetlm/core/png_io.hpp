#pragma once
// PNG images through libpng (core/png_io.cpp).
#include <cstdint>
#include <string>

#include "shadetlm/core/texture.hpp"

namespace shadetlm::core {

// The image as RGBA in [0, 1] (values as stored: display-encoded), at most max_texels
// texels (refused before decoding). Throws InputError naming the file and the fault: a
// CRC, a truncated stream, a pixel past its palette, an image too large.
Texture read_png(const std::string& path, uint64_t max_texels);

}  // namespace shadetlm::core
