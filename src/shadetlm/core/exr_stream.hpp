#pragma once
// Writing an EXR straight into a file as OpenEXR encodes it (the io component:
// frame_io.cpp for frames and maps, bump_map_io.cpp for normal maps' mip chains).
// OpenEXR writes its offset table from the output file's destructor, which swallows a
// failed write; the stream keeps the first failure, so none goes unseen.
#include <functional>
#include <string>

#include <ImfHeader.h>
#include <ImfIO.h>

namespace shadetlm::core {

// Sets the header's compression and zlib level to those of set_exr_compression
// (core/frame.hpp; zip at kDefaultZipLevel by default).
void compress_as_set(Imf::Header& header);

// Opens `file` (a temporary), calls write(stream) to put the EXR into it, and closes it;
// any failure, in the writes, the offset table or the close, throws std::runtime_error
// naming `output`, the file the temporary becomes.
void write_exr_stream(const std::string& file, const std::string& output,
                      const std::function<void(Imf::OStream&)>& write);

}  // namespace shadetlm::core
