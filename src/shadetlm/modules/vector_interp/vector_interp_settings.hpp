#pragma once
// The L and H interpolator's settings, pipeline.vector_interp.<key> (core/setting_fields.hpp):
// setup reads them too, since it sets up the planes they step.
#include "shadetlm/core/setting_fields.hpp"

namespace shadetlm::modules {

struct VectorInterpSettings {
  static constexpr const char* block = "vector_interp";
  enum class BumpVectors { Unit, Affine } bump_vectors = BumpVectors::Unit;
  enum class H { Pixel, Interpolated } h = H::Pixel;

  bool affine_bump_vectors() const { return bump_vectors == BumpVectors::Affine; }
  bool interpolate_h() const { return h == H::Interpolated; }

  template <class F>
  void fields(F& f) {
    f(bump_vectors, "bump_vectors", {"unit", "affine"},
      "fetched-normal bump paths: interpolate unit L and H (the paper's) or L and V as affine vectors");
    f(h, "h", {"pixel", "interpolated"},
      "world-space paths: H = normalize(L + V) of the unit L and V at each pixel, or H at the vertices "
      "interpolated and normalized (Fig. 1 of the bump-mapping paper)");
  }
};

}  // namespace shadetlm::modules
