#include "shadetlm/core/frame.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include <unistd.h>


#include "shadetlm/core/input_error.hpp"
#include "shadetlm/core/texture.hpp"

namespace shadetlm::core {

std::vector<float>& Frame::add(const std::string& name, float fill) {
  for (auto& c : channels)
    if (c.name == name) return c.values;
  channels.push_back({name, std::vector<float>(pixel_count(), fill)});
  return channels.back().values;
}

const Channel* Frame::find(const std::string& name) const {
  for (const auto& c : channels)
    if (c.name == name) return &c;
  return nullptr;
}

std::vector<float>& Frame::at(const std::string& name) {
  for (auto& c : channels)
    if (c.name == name) return c.values;
  throw std::out_of_range("the frame has no channel " + name);
}

const std::vector<float>& Frame::at(const std::string& name) const {
  const Channel* c = find(name);
  if (!c) throw std::out_of_range("the frame has no channel " + name);
  return c->values;
}

}  // namespace shadetlm::core
