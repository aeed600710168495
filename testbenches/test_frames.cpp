// EXR frames: channels, types, compression and attributes survive a round trip, and a
// failed write leaves nothing behind.
#include <filesystem>
#include <fstream>

#include <ImfChannelList.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfFrameBuffer.h>
#include <half.h>

#include "shadetlm/core/frame.hpp"
#include "test_util.hpp"

using namespace shadetlm;  // core::, modules::, reference::

namespace fs = std::filesystem;

namespace {
core::Frame sample_frame() {
  core::Frame f(5, 3);
  for (const char* n : {"R", "G", "B", "A", "Z", "N.X", "N.Y", "N.Z", "debug.iterations"}) {
    auto& v = f.add(n);
    for (size_t i = 0; i < v.size(); ++i) v[i] = float(i) * 0.1f + float(n[0]) + 1e-7f;
  }
  f.at("Z")[4] = std::numeric_limits<float>::infinity();
  f.attributes["shadetlm:version"] = "9.9";
  f.attributes["shadetlm:config"] = R"({"normalize.mode":"exact"})";
  return f;
}
}  // namespace

TEST_CASE("an EXR frame round-trips its channels and attributes as float", "[frames]") {
  const auto dir = test::temp_dir("exr");
  const std::string path = (dir / "f.exr").string();
  const core::Frame f = sample_frame();
  core::write_exr(path, f);
  const core::Frame g = core::read_exr(path);
  REQUIRE(g.width == 5);
  REQUIRE(g.height == 3);
  REQUIRE(g.channels.size() == f.channels.size());
  for (const auto& c : f.channels) {
    INFO(c.name);
    REQUIRE(g.find(c.name));
    CHECK(g.at(c.name) == c.values);  // bit-exact: float, not half
  }
  CHECK(g.attributes.at("shadetlm:version") == "9.9");
  CHECK(g.attributes.at("shadetlm:config") == f.attributes.at("shadetlm:config"));

  Imf::InputFile in(path.c_str());
  CHECK(in.header().compression() == Imf::ZIP_COMPRESSION);
  for (auto it = in.header().channels().begin(); it != in.header().channels().end(); ++it)
    CHECK(it.channel().type == Imf::FLOAT);
  CHECK(!in.header().hasTileDescription());  // single part, scan lines
}

TEST_CASE("half channels are read as float", "[frames]") {
  const auto dir = test::temp_dir("exr-half");
  const std::string path = (dir / "h.exr").string();
  std::vector<half> values = {half(0.5f), half(1.25f), half(-2.0f), half(3.0f)};
  Imf::Header header(2, 2);
  header.channels().insert("Y", Imf::Channel(Imf::HALF));
  Imf::FrameBuffer fb;
  fb.insert("Y", Imf::Slice(Imf::HALF, (char*)values.data(), sizeof(half), 2 * sizeof(half)));
  {
    Imf::OutputFile out(path.c_str(), header);
    out.setFrameBuffer(fb);
    out.writePixels(2);
  }
  const core::Frame f = core::read_exr(path);
  CHECK(f.at("Y") == std::vector<float>{0.5f, 1.25f, -2.0f, 3.0f});
}

TEST_CASE("a failed write leaves no file, partial or temporary", "[frames]") {
  const auto dir = test::temp_dir("exr-fail");
  // A folder that cannot be made (a file stands in its place).
  { std::ofstream((dir / "a-file").string()) << "x"; }
  const std::string path = (dir / "a-file" / "f.exr").string();
  CHECK_THROWS(core::write_exr(path, sample_frame()));
  CHECK(!fs::exists(path));
  // A failed rename (the target is a folder) leaves no temporary behind.
  std::filesystem::create_directories(dir / "taken.exr" / "inside");
  CHECK_THROWS(core::write_exr((dir / "taken.exr").string(), sample_frame()));
  // A successful write leaves the frame and nothing else.
  core::write_exr((dir / "ok.exr").string(), sample_frame());
  int files = 0;
  for (const auto& e : fs::directory_iterator(dir)) files += e.is_regular_file();
  CHECK(files == 2);  // a-file and ok.exr only
}

TEST_CASE("a file that is not an EXR is reported by name", "[frames][bad]") {
  const auto dir = test::temp_dir("exr-bad");
  const std::string path = (dir / "x.exr").string();
  std::FILE* f = std::fopen(path.c_str(), "w");
  std::fputs("hello", f);
  std::fclose(f);
  try {
    core::read_exr(path);
    FAIL("no error");
  } catch (const core::InputError& e) {
    CHECK(e.file() == path);
  }
}

TEST_CASE("the PNG preview is sRGB-encoded and clamped", "[frames]") {
  const auto dir = test::temp_dir("png-preview");
  core::Frame f(2, 1);
  f.add("R") = {0.5f, 2.0f};
  f.add("G") = {0.0f, -1.0f};
  f.add("B") = {0.0031308f, std::numeric_limits<float>::quiet_NaN()};
  const std::string path = (dir / "p.png").string();
  core::write_png_preview(path, f);
  const core::Texture t = core::load_texture_file(path);
  CHECK(t.texel(0, 0).r == Approx(std::lround(core::linear_to_srgb(0.5) * 255) / 255.0).margin(1e-6));
  CHECK(t.texel(1, 0).r == Approx(1.0));
  CHECK(t.texel(1, 0).g == Approx(0.0));
  CHECK(t.texel(1, 0).b == Approx(0.0));
}
