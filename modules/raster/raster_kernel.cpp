#include "shadetlm/modules/raster/raster_kernel.hpp"

namespace shadetlm::modules {

RasterKernel::RasterKernel(int width, int height)
    : width_(width), height_(height), inv_depth_(size_t(width) * height, 0.0f) {}

}  // namespace shadetlm::modules
