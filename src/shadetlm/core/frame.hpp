#pragma once
// A frame as written to EXR: named float channels of one resolution, plus string
// attributes for the header. Standard channels: R, G, B, A (colour, linear), Z (eye-
// space depth, +inf where nothing is covered), N.X, N.Y, N.Z (world-space unit normal).
#include <map>
#include <string>
#include <vector>

#include "shadetlm/core/output.hpp"  // how every output is written

namespace shadetlm::core {

struct Channel {
  std::string name;
  std::vector<float> values;  // row-major, row 0 at the top
};

struct Frame {
  int width = 0, height = 0;
  std::vector<Channel> channels;
  std::map<std::string, std::string> attributes;  // e.g. "shadetlm:version"

  Frame() = default;
  Frame(int w, int h) : width(w), height(h) {}

  // Adds a channel filled with `fill`, or returns the existing one. The reference is
  // valid until the next add (which may move the channels; their buffers stay put).
  std::vector<float>& add(const std::string& name, float fill = 0.0f);
  const Channel* find(const std::string& name) const;
  std::vector<float>& at(const std::string& name);
  const std::vector<float>& at(const std::string& name) const;
  size_t pixel_count() const { return size_t(width) * height; }
};

// ---- The io component (shadetlm::io, linked apart: file formats) from here on.
// How EXR files are written, for the whole process (the --compression and --threads
// options): OpenEXR's lossless compressions (none, rle, zips, zip, piz; a lossy name
// or an unknown one is an InputError naming --compression), zip:L and zips:L with
// zlib's level L (1 fastest, 9 smallest), zip at kDefaultZipLevel by default
// (docs/performance.md, "Writing frames"); and the threads of OpenEXR's pool, which compress and
// decompress a file's blocks in parallel (1: none, on the calling thread).
constexpr int kDefaultZipLevel = 4;  // (OpenEXR's own default)
const std::vector<std::string>& exr_compression_names();
void set_exr_compression(const std::string& name);
void set_exr_threads(int threads);
// Writes a single-part EXR, compressed as set above, with every channel as 32-bit float and the
// attributes as string attributes. The file appears only when complete: it is written
// beside the target and renamed. Throws std::runtime_error naming the path on failure.
void write_exr(const std::string& path, const Frame& frame);
// The same, straight into `file` (a temporary of an OutputSet), streamed as OpenEXR
// compresses it; errors name `output`, the file it becomes.
void write_exr_to(const std::string& file, const std::string& output, const Frame& frame);
// Reads every channel (half and uint are converted to float) and the string attributes.
// Throws InputError naming the path.
Frame read_exr(const std::string& path);
// Writes R, G, B as an 8-bit sRGB PNG (clamped to [0, 1]), also through a rename.
void write_png_preview(const std::string& path, const Frame& frame);
// Writes one channel as a heat map PNG (black, blue, red, yellow, white from 0 to
// max_value; larger values white), also through a rename.
void write_heat_map_png(const std::string& path, const Frame& frame, const std::string& channel, float max_value);
// The same PNGs as bytes (to write with an OutputSet); an 8-bit RGB image's PNG.
std::string png_preview(const Frame& frame);
std::string heat_map_png(const Frame& frame, const std::string& channel, float max_value);
std::string encode_png(int width, int height, const std::vector<unsigned char>& rgb);

}  // namespace shadetlm::core
