// Frames in and out of files (the io component): EXR and PNG.
#include <algorithm>
#include <cerrno>
#include <cstring>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <ImfThreading.h>
#include <png.h>

#include <fcntl.h>
#include <unistd.h>

#include "shadetlm/core/input_file.hpp"
#include "shadetlm/core/frame.hpp"
#include "shadetlm/core/exr_stream.hpp"
#include "shadetlm/core/input_error.hpp"
#include "shadetlm/core/output.hpp"
#include "shadetlm/core/texture.hpp"

namespace shadetlm::core {

namespace {
// How frames and maps are compressed (set_exr_compression): OpenEXR's lossless methods
// only, so that a frame read back is the frame the model computed.
struct Method {
  const char* name;
  Imf::Compression compression;
};
constexpr Method kLossless[] = {{"none", Imf::NO_COMPRESSION},   {"rle", Imf::RLE_COMPRESSION},
                                {"zips", Imf::ZIPS_COMPRESSION}, {"zip", Imf::ZIP_COMPRESSION},
                                {"piz", Imf::PIZ_COMPRESSION}};
Imf::Compression exr_compression = Imf::ZIP_COMPRESSION;
int exr_zip_level = kDefaultZipLevel;  // zlib's level for zip and zips
const char* const kNames = "none, rle, zips, zip, piz, or zip:L / zips:L with zlib's level L from 1 to 9";
}  // namespace

const std::vector<std::string>& exr_compression_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const Method& m : kLossless) n.push_back(m.name);
    return n;
  }();
  return names;
}

void set_exr_compression(const std::string& name) {
  // "zip:L" and "zips:L": the method and zlib's level (OpenImageIO's spelling).
  const size_t colon = name.find(':');
  const std::string method = name.substr(0, colon);
  int level = kDefaultZipLevel;
  if (colon != std::string::npos) {
    const std::string digits = name.substr(colon + 1);
    if ((method != "zip" && method != "zips") || digits.size() != 1 || digits[0] < '1' || digits[0] > '9')
      throw InputError("--compression", name, std::string("a level is zip:L or zips:L with L from 1 to 9 (") + kNames + ")");
    level = digits[0] - '0';
  }
  for (const Method& m : kLossless)
    if (method == m.name) {
      exr_compression = m.compression, exr_zip_level = level;
      return;
    }
  for (const char* lossy : {"pxr24", "b44", "b44a", "dwaa", "dwab"})
    if (name == lossy)
      throw InputError("--compression", name,
                       "is lossy for 32-bit float channels (a frame read back would not be the model's): use none, "
                       "rle, zips, zip or piz");
  throw InputError("--compression", name, std::string("unknown: one of ") + kNames + " (OpenEXR's lossless methods)");
}

void set_exr_threads(int threads) {
  SignalsHeld held;  // the pool's threads never take SIGINT or SIGTERM: the main thread does
  try {
    Imf::setGlobalThreadCount(threads > 1 ? threads : 0);  // (0: compress on the calling thread)
  } catch (const std::exception& e) {
    try {
      Imf::setGlobalThreadCount(0);
    } catch (const std::exception&) {
    }
    throw InputError("--threads", std::to_string(threads),
                     std::string("OpenEXR's pool of that many threads cannot be started: ") + e.what());
  }
}

namespace {
// OpenEXR's output onto a file: positioned writes (OpenEXR seeks back to fill in its
// offset table), each checked. OpenEXR writes that table from OutputFile's destructor,
// which swallows exceptions, so the first failure is also kept for error().
class FileStream : public Imf::OStream {
 public:
  FileStream(int fd, const std::string& name) : Imf::OStream(name.c_str()), fd_(fd) {}
  void write(const char c[], int n) override {
    while (n > 0) {
      const ssize_t w = ::pwrite(fd_, c, size_t(n), off_t(pos_));
      if (w < 0 && errno == EINTR) continue;
      if (w <= 0) {
        if (error_ == 0) error_ = w < 0 ? errno : ENOSPC;
        throw std::runtime_error(std::strerror(error_));
      }
      c += w, n -= int(w), pos_ += uint64_t(w);
    }
  }
  uint64_t tellp() override { return pos_; }
  void seekp(uint64_t pos) override { pos_ = pos; }
  int error() const { return error_; }

 private:
  int fd_;
  uint64_t pos_ = 0;
  int error_ = 0;
};
}  // namespace

void compress_as_set(Imf::Header& header) {
  header.compression() = exr_compression;
  header.zipCompressionLevel() = exr_zip_level;
}

void write_exr_stream(const std::string& file, const std::string& output,
                      const std::function<void(Imf::OStream&)>& write) {
  const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) throw std::runtime_error(output + ": cannot write the file: " + std::strerror(errno));
  int error = 0;
  try {
    FileStream stream(fd, output);
    write(stream);  // (the offset table written as its output file is destroyed, inside)
    error = stream.error();
  } catch (const std::exception& e) {
    ::close(fd);
    throw std::runtime_error(output + ": cannot write the EXR: " + e.what());
  }
  if (::close(fd) != 0 && error == 0) error = errno;
  if (error != 0) throw std::runtime_error(output + ": cannot write the file: " + std::strerror(error));
}

void write_exr_to(const std::string& file, const std::string& output, const Frame& frame) {
  write_exr_stream(file, output, [&](Imf::OStream& stream) {
    Imf::Header header(frame.width, frame.height);
    compress_as_set(header);
    for (const auto& [k, v] : frame.attributes) header.insert(k, Imf::StringAttribute(v));
    Imf::FrameBuffer fb;
    for (const auto& c : frame.channels) {
      header.channels().insert(c.name, Imf::Channel(Imf::FLOAT));
      fb.insert(c.name, Imf::Slice(Imf::FLOAT, (char*)c.values.data(), sizeof(float), sizeof(float) * frame.width));
    }
    Imf::OutputFile out(stream, header);
    out.setFrameBuffer(fb);
    out.writePixels(frame.height);
  });
}

void write_exr(const std::string& path, const Frame& frame) {
  write_atomically(path, [&](const std::string& tmp) { write_exr_to(tmp, path, frame); });
}

Frame read_exr(const std::string& path) {
  check_input_file(path, "", kMaxImageBytes);
  try {
    Imf::InputFile in(path.c_str());
    const Imf::Header& h = in.header();
    const Imath::Box2i dw = h.dataWindow();
    Frame f(dw.max.x - dw.min.x + 1, dw.max.y - dw.min.y + 1);
    Imf::FrameBuffer fb;
    for (auto it = h.channels().begin(); it != h.channels().end(); ++it) {
      std::vector<float>& v = f.add(it.name());
      // The slice's origin is pixel (0, 0) of the data window's coordinate system.
      char* base = (char*)(v.data() - dw.min.x - size_t(dw.min.y) * f.width);
      fb.insert(it.name(), Imf::Slice(Imf::FLOAT, base, sizeof(float), sizeof(float) * f.width));
    }
    in.setFrameBuffer(fb);
    in.readPixels(dw.min.y, dw.max.y);
    for (auto it = h.begin(); it != h.end(); ++it)
      if (auto* s = dynamic_cast<const Imf::StringAttribute*>(&it.attribute()))
        f.attributes[it.name()] = s->value();
    return f;
  } catch (const std::exception& e) {
    throw InputError(path, "", std::string("cannot read the EXR: ") + e.what());
  }
}

// An 8-bit RGB PNG in memory, through libpng (its errors are returned, where stb's
// encoder asserts when an allocation fails), to write with checked writes.
std::string encode_png(int width, int height, const std::vector<unsigned char>& rgb) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = png_uint_32(width), image.height = png_uint_32(height);
  image.format = PNG_FORMAT_RGB;
  png_alloc_size_t size = 0;  // first its size, then the bytes
  if (png_image_write_get_memory_size(image, size, 0, rgb.data(), 0, nullptr)) {
    std::string bytes(size, '\0');
    if (png_image_write_to_memory(&image, bytes.data(), &size, 0, rgb.data(), 0, nullptr)) {
      bytes.resize(size);
      return bytes;
    }
  }
  const std::string why = image.message;
  png_image_free(&image);
  throw std::runtime_error("cannot encode the PNG: " + why);
}

std::string png_preview(const Frame& frame) {
  const char* names[3] = {"R", "G", "B"};
  std::vector<unsigned char> rgb(frame.pixel_count() * 3);
  for (int k = 0; k < 3; ++k) {
    const std::vector<float>& c = frame.at(names[k]);
    for (size_t i = 0; i < frame.pixel_count(); ++i) {
      double v = std::isfinite(c[i]) ? std::clamp(double(c[i]), 0.0, 1.0) : 0.0;
      rgb[i * 3 + k] = static_cast<unsigned char>(std::lround(linear_to_srgb(v) * 255.0));
    }
  }
  return encode_png(frame.width, frame.height, rgb);
}

std::string heat_map_png(const Frame& frame, const std::string& channel, float max_value) {
  const std::vector<float>& c = frame.at(channel);
  std::vector<unsigned char> rgb(frame.pixel_count() * 3);
  // A ramp black → blue → red → yellow → white, piecewise linear in the value.
  static const float stops[5][3] = {{0, 0, 0}, {0.1f, 0.2f, 0.9f}, {0.9f, 0.1f, 0.1f}, {1, 0.9f, 0.1f}, {1, 1, 1}};
  for (size_t i = 0; i < frame.pixel_count(); ++i) {
    const float v = std::isfinite(c[i]) && max_value > 0 ? std::clamp(c[i] / max_value, 0.0f, 1.0f) : 0.0f;
    const float x = v * 4;
    const int k = std::min(3, int(x));
    const float f = x - float(k);
    for (int j = 0; j < 3; ++j)
      rgb[i * 3 + size_t(j)] = static_cast<unsigned char>(std::lround(255 * (stops[k][j] + (stops[k + 1][j] - stops[k][j]) * f)));
  }
  return encode_png(frame.width, frame.height, rgb);
}

void write_png_preview(const std::string& path, const Frame& frame) { write_file(path, png_preview(frame)); }

void write_heat_map_png(const std::string& path, const Frame& frame, const std::string& channel, float max_value) {
  write_file(path, heat_map_png(frame, channel, max_value));
}

}  // namespace shadetlm::core
