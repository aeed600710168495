#pragma once
// The normal interpolator's settings, pipeline.normal_interp.<key> (core/setting_fields.hpp):
// setup and bump_perturb read its mode too, since they set up and step the same planes.
#include "shadetlm/core/setting_fields.hpp"

namespace shadetlm::modules {

struct NormalInterpSettings {
  static constexpr const char* block = "normal_interp";
  enum class Mode { Affine, Perspective } mode = Mode::Perspective;
  enum class Reseed { None, Line, Tile8, Tile16, Tile32 } reseed = Reseed::None;

  bool perspective() const { return mode == Mode::Perspective; }
  // The kernel's reseed interval: 0 none, −1 each row start, N every N pixels as well.
  int reseed_interval() const {
    switch (reseed) {
      case Reseed::None: return 0;
      case Reseed::Line: return -1;
      case Reseed::Tile8: return 8;
      case Reseed::Tile16: return 16;
      default: return 32;
    }
  }

  template <class F>
  void fields(F& f) {
    f(mode, "mode", {"affine", "perspective"}, "constant increments of N (affine) or of N/w and 1/w (perspective)");
    f(reseed, "reseed", {"none", "line", "tile8", "tile16", "tile32"},
      "walk the whole triangle from its seed, or take every row start (and every 8, 16, 32 pixels) from the plane");
  }
};

}  // namespace shadetlm::modules
