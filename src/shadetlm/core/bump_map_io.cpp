// Mip chains of normal maps written as tiled EXR (the io component).
#include <ImfChannelList.h>
#include <ImfCompression.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfStringAttribute.h>
#include <ImfTiledOutputFile.h>

#include "shadetlm/core/bump_map.hpp"
#include "shadetlm/core/exr_stream.hpp"
#include "shadetlm/core/frame.hpp"
#include "shadetlm/core/input_error.hpp"

namespace shadetlm::core {

void write_mip_chain(const std::string& path, const Texture& base, const std::vector<Texture>& levels,
                     const std::vector<std::pair<std::string, std::string>>& attributes) {
  write_atomically(path, [&](const std::string& tmp) {
    write_exr_stream(tmp, path, [&](Imf::OStream& stream) {
      Imf::Header header(base.width, base.height);
      compress_as_set(header);
      header.setTileDescription(Imf::TileDescription(64, 64, Imf::MIPMAP_LEVELS, Imf::ROUND_DOWN));
      for (const auto& [k, v] : attributes) header.insert(k, Imf::StringAttribute(v));
      const char* names[3] = {"R", "G", "B"};
      for (const char* n : names) header.channels().insert(n, Imf::Channel(Imf::FLOAT));
      Imf::TiledOutputFile out(stream, header);
      if (out.numLevels() != int(levels.size()) + 1)
        throw std::runtime_error("the mip chain does not match the EXR's levels");
      for (int l = 0; l < out.numLevels(); ++l) {
        const Texture& t = l == 0 ? base : levels[size_t(l) - 1];
        std::vector<float> planes[3];
        for (int c = 0; c < 3; ++c) {
          planes[c].resize(t.texels.size());
          for (size_t i = 0; i < t.texels.size(); ++i) planes[c][i] = t.texels[i][c];
        }
        Imf::FrameBuffer fb;
        for (int c = 0; c < 3; ++c)
          fb.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(planes[c].data()), sizeof(float),
                                         sizeof(float) * size_t(t.width)));
        out.setFrameBuffer(fb);
        out.writeTiles(0, out.numXTiles(l) - 1, 0, out.numYTiles(l) - 1, l);
      }
    });
  });
}

}  // namespace shadetlm::core
