// Distance and cone maps in and out of EXR files (the io component).
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "shadetlm/core/frame.hpp"
#include "shadetlm/core/input_error.hpp"
#include "shadetlm/core/parallax_map.hpp"

namespace shadetlm::core {

namespace {

std::string slice_name(int k) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "d.%03d", k);
  return buf;
}

int attribute_int(const Frame& f, const std::string& path, const std::string& name) {
  auto it = f.attributes.find(name);
  if (it == f.attributes.end()) throw InputError(path, name, "missing from the header");
  try {
    return std::stoi(it->second);
  } catch (const std::exception&) {
    throw InputError(path, name, "is not a number: \"" + it->second + "\"");
  }
}

// The map's kind, one of `kinds` (their names joined by " or " in the message).
void check_kind(const Frame& f, const std::string& path, const std::vector<std::string>& kinds) {
  auto it = f.attributes.find("shadetlm:map");
  if (it == f.attributes.end())
    throw InputError(path, "shadetlm:map", "missing: not a map written by shadetlm precompute");
  if (std::find(kinds.begin(), kinds.end(), it->second) != kinds.end()) return;
  std::string expected;
  for (const std::string& k : kinds) expected += (expected.empty() ? "\"" : " or \"") + k + "\"";
  throw InputError(path, "shadetlm:map", "is \"" + it->second + "\", expected " + expected);
}

// FNV-1a over the map's channels, names and float values, in the order of their names
// (an EXR file's): written as shadetlm:checksum, so that a map whose header still
// matches its scene but whose data was changed or damaged is refused.
std::string data_checksum(const Frame& f) {
  std::vector<const Channel*> channels;
  for (const Channel& c : f.channels) channels.push_back(&c);
  std::sort(channels.begin(), channels.end(), [](const Channel* a, const Channel* b) { return a->name < b->name; });
  Fnv1a h;
  for (const Channel* c : channels) {
    h.mix(c->name.c_str(), c->name.size() + 1);
    h.mix(c->values.data(), c->values.size() * sizeof(float));
  }
  return h.hex();
}

void write_map(const std::string& path, Frame& f) {
  f.attributes["shadetlm:checksum"] = data_checksum(f);
  write_exr(path, f);
}

void check_data(const Frame& f, const std::string& path) {
  const auto it = f.attributes.find("shadetlm:checksum");
  if (it == f.attributes.end())
    throw InputError(path, "shadetlm:checksum", "missing: a map written before maps carried one; precompute it again");
  if (it->second != data_checksum(f))
    throw InputError(path, "shadetlm:checksum",
                     "does not match the map's data (the file was changed or damaged); precompute it again");
}

}  // namespace

void write_volume_map(const std::string& path, const VolumeMap& map, const std::string& kind) {
  Frame f(map.width, map.height);
  f.attributes = map.params;
  f.attributes["shadetlm:map"] = kind;
  const size_t cells = size_t(map.width) * size_t(map.height);
  for (int k = 0; k < map.slices; ++k) {
    std::vector<float>& c = f.add(slice_name(k));
    std::copy(map.values.begin() + ptrdiff_t(size_t(k) * cells), map.values.begin() + ptrdiff_t(size_t(k + 1) * cells),
              c.begin());
  }
  write_map(path, f);
}

VolumeMap read_volume_map(const std::string& path) {
  const Frame f = read_exr(path);
  check_kind(f, path, {"box-gap", "refined", "donnelly", "distance"});
  check_data(f, path);
  VolumeMap m;
  m.width = f.width, m.height = f.height;
  m.slices = attribute_int(f, path, "shadetlm:slices");
  if (m.slices < 1 || m.slices > 1024) throw InputError(path, "shadetlm:slices", "must be in [1, 1024]");
  const size_t cells = f.pixel_count();
  m.values.resize(cells * size_t(m.slices));
  for (int k = 0; k < m.slices; ++k) {
    const Channel* c = f.find(slice_name(k));
    if (!c) throw InputError(path, slice_name(k), "channel missing (the header says " + std::to_string(m.slices) + " slices)");
    for (size_t i = 0; i < cells; ++i) {
      if (!std::isfinite(c->values[i]) || c->values[i] < 0)
        throw InputError(path, slice_name(k), "holds a negative or non-finite distance");
      m.values[size_t(k) * cells + i] = c->values[i];
    }
  }
  m.params = f.attributes;
  if (m.params["shadetlm:map"] == "distance") m.params["shadetlm:map"] = "box-gap";  // its name before Donnelly's map
  return m;
}

void write_cone_map(const std::string& path, const ConeMap& map) {
  Frame f(map.width, map.height);
  f.attributes = map.params;
  f.add("apex") = map.apex;
  f.add("ratio") = map.ratio;
  write_map(path, f);
}

ConeMap read_cone_map(const std::string& path) {
  const Frame f = read_exr(path);
  check_kind(f, path, {"cone", "relaxed-cone"});
  check_data(f, path);
  ConeMap m;
  m.width = f.width, m.height = f.height;
  m.slices = attribute_int(f, path, "shadetlm:slices");
  if (m.slices < 1 || m.slices > 1024) throw InputError(path, "shadetlm:slices", "must be in [1, 1024]");
  for (const char* name : {"apex", "ratio"}) {
    const Channel* c = f.find(name);
    if (!c) throw InputError(path, name, "channel missing");
    for (float v : c->values)
      if (!std::isfinite(v) || v < 0) throw InputError(path, name, "holds a negative or non-finite value");
    (std::string(name) == "apex" ? m.apex : m.ratio) = c->values;
  }
  m.params = f.attributes;
  return m;
}

}  // namespace shadetlm::core
