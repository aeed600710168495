#pragma once
// Settings as structs (docs/development.md, "Adding a setting"). A struct lists its
// fields once, in a member template that the settings table and the reader both walk;
// each field's default is the member's initializer:
//
//   struct NormalizeSettings {
//     static constexpr const char* block = "normalize";  // its keys are normalize.<key>
//     NormalizeMode mode = NormalizeMode::Exact;
//     template <class F> void fields(F& f) {
//       f(mode, "mode", normalize_mode_names(), "how the normal is normalized");
//     }
//   };
//
// specs_of(S{}) gives its SettingSpecs (what PipelineConfig::resolve checks, and the
// docs' list), read<S>(settings, prefix) the struct of a scene's resolved values. An
// enum's names are in the order of its values, so a name is its value's index.
#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "shadetlm/core/pipeline_config.hpp"

namespace shadetlm::core {

struct Range {
  double min, max;
};

// A number format's name (core::NumberFormat); a block's may be "default", which takes
// pipeline.number_format.
struct FormatName {
  std::string name;
};

// Writes each field as a SettingSpec; the field's value is its default.
class SpecWriter {
 public:
  explicit SpecWriter(std::string prefix = "") : prefix_(std::move(prefix)) {}
  void operator()(bool& v, const std::string& key, const std::string& doc) { add(key, v, doc); }
  void operator()(int& v, const std::string& key, Range r, const std::string& doc) { add(key, v, doc, {}, r); }
  void operator()(uint32_t& v, const std::string& key, Range r, const std::string& doc) { add(key, v, doc, {}, r); }
  void operator()(uint64_t& v, const std::string& key, Range r, const std::string& doc) { add(key, v, doc, {}, r); }
  void operator()(double& v, const std::string& key, Range r, const std::string& doc) { add(key, v, doc, {}, r); }
  void operator()(std::string& v, const std::string& key, const std::vector<std::string>& choices, const std::string& doc) {
    add(key, v, doc, choices);
  }
  void operator()(FormatName& v, const std::string& key, const std::string& doc) {
    add(key, v.name, doc);
    specs.back().number_format = true;
  }
  template <class E, std::enable_if_t<std::is_enum_v<E>, int> = 0>
  void operator()(E& v, const std::string& key, const std::vector<std::string>& names, const std::string& doc) {
    add(key, names.at(size_t(v)), doc, names);
  }
  std::vector<SettingSpec> specs;

 private:
  void add(const std::string& key, nlohmann::json fallback, const std::string& doc, std::vector<std::string> choices = {},
           Range r = {0, 0}) {
    specs.push_back({prefix_ + key, std::move(fallback), std::move(choices), r.min, r.max, doc});
  }
  std::string prefix_;
};

// Reads each field from resolved settings (PipelineConfig::resolve has checked them).
class SettingsReader {
 public:
  SettingsReader(const Settings& s, std::string prefix) : s_(s), prefix_(std::move(prefix)) {}
  void operator()(bool& v, const std::string& key, const std::string&) { v = s_.boolean(prefix_ + key); }
  void operator()(int& v, const std::string& key, Range, const std::string&) { v = s_.integer(prefix_ + key); }
  void operator()(uint32_t& v, const std::string& key, Range, const std::string&) { v = uint32_t(s_.integer(prefix_ + key)); }
  void operator()(uint64_t& v, const std::string& key, Range, const std::string&) { v = uint64_t(s_.integer(prefix_ + key)); }
  void operator()(double& v, const std::string& key, Range, const std::string&) { v = s_.number(prefix_ + key); }
  void operator()(std::string& v, const std::string& key, const std::vector<std::string>&, const std::string&) {
    v = s_.string(prefix_ + key);
  }
  void operator()(FormatName& v, const std::string& key, const std::string&) { v.name = s_.string(prefix_ + key); }
  template <class E, std::enable_if_t<std::is_enum_v<E>, int> = 0>
  void operator()(E& v, const std::string& key, const std::vector<std::string>& names, const std::string&) {
    const std::string& name = s_.string(prefix_ + key);
    const auto it = std::find(names.begin(), names.end(), name);
    if (it == names.end()) throw std::logic_error("setting " + prefix_ + key + ": unchecked value " + name);
    v = E(it - names.begin());
  }

 private:
  const Settings& s_;
  std::string prefix_;
};

// The settings table of a struct, from the defaults it is given.
template <class S>
std::vector<SettingSpec> specs_of(S defaults, const std::string& prefix = "") {
  SpecWriter w(prefix);
  defaults.fields(w);
  return std::move(w.specs);
}

// The struct of resolved settings (its keys prefix + key); `out` holds what fields()
// needs to know besides the values (which fields a block has).
template <class S>
S read(const Settings& s, const std::string& prefix, S out = S{}) {
  SettingsReader r(s, prefix);
  out.fields(r);
  return out;
}

}  // namespace shadetlm::core
