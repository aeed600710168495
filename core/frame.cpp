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

std::string temporary_path_for(const std::string& path) {
  return path + ".tmp." + std::to_string(::getpid());
}

void remove_quietly(const std::string& path) {
  std::error_code ec;
  std::filesystem::remove(path, ec);
}

void rename_into_place(const std::string& tmp, const std::string& path) {
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    remove_quietly(tmp);
    throw std::runtime_error(path + ": cannot write the file: " + ec.message());
  }
}

}  // namespace shadetlm::core
