#include "core/pipeline_config.hpp"

#include <cmath>
#include <stdexcept>

#include "core/input_error.hpp"
#include "core/number_format.hpp"

namespace core {

using json = nlohmann::json;

const std::vector<SettingSpec>& pipeline_settings() {
  // Read by the SystemC pipeline (`shadetlm render`); the golden model reads none of
  // them. docs/configuration.md documents each one (a test checks that it does).
  static std::vector<SettingSpec> table = {
      {"clock_mhz", 500.0, {}, 1, 100000, "clock of every block, for simulated time"},
      {"number_format", "float32", {}, 0, 0,
       "number format of every datapath: float32, float16 or fixed:I.F (docs/numerical-stability.md)", true},
      {"elaborate", "needed", {"needed", "all"}, 0, 0,
       "elaborate the blocks some material needs, or every block (to measure what skipping saves)"},
      {"normal_interp.mode", "perspective", {"affine", "perspective"}, 0, 0,
       "constant increments of N (affine) or of N/w and 1/w (perspective)"},
      {"normal_interp.reseed", "none", {"none", "line", "tile8", "tile16", "tile32"}, 0, 0,
       "walk the whole triangle from its seed, or take every row start (and every 8, 16, 32 pixels) from the plane"},
      {"normalize.mode", "exact", {"exact", "forward-difference", "rsqrt0", "rsqrt1", "rsqrt2"},
       0, 0, "how the normal is normalized"},
      {"vector_interp.bump_vectors", "unit", {"unit", "affine"}, 0, 0,
       "fetched-normal bump paths: interpolate unit L and H (the paper's) or L and V as affine vectors"},
      {"texture_fetch.filter", "trilinear", {"nearest", "bilinear", "trilinear", "anisotropic", "ewa"}, 0, 0,
       "screen-space filter of texture-screen materials"},
      {"texture_fetch.probes", 4, {}, 1, 16, "anisotropic filter: trilinear probes along the footprint's major axis"},
      {"texel_project.units", 4, {}, 1, 64, "parallel splat units of texel_project"},
      {"bump_fetch.filter", "trilinear", {"nearest", "bilinear", "trilinear", "anisotropic"}, 0, 0,
       "texture filter of the bump fetch (nearest and bilinear on the nearest mip level)"},
      {"bump_fetch.probes", 4, {}, 1, 16, "anisotropic filter: trilinear probes along the footprint's major axis"},
      {"bump_fetch.renormalize_mips", true, {}, 0, 0,
       "normal maps built on load: renormalize the texels of every mip level"},
  };
  // Every block's timing: latency (cycles to its first result) and initiation interval
  // (cycles per unit of work). Model defaults, not figures from the papers.
  static const bool timing_added = [] {
    const std::pair<const char*, std::pair<int, int>> blocks[] = {
        {"setup", {16, 8}},         {"raster", {4, 1}},         {"normal_interp", {2, 1}},
        {"bump_fetch", {24, 1}},    {"bump_perturb", {8, 1}},   {"normal_mux", {1, 1}},
        {"normalize", {12, 1}},     {"vector_interp", {20, 1}}, {"texture_fetch", {8, 1}},
        {"lighting", {10, 1}},      {"framebuffer", {2, 1}},    {"texel_project", {16, 1}},
        {"parallax", {16, 1}}};
    for (const auto& [block, t] : blocks) {
      table.push_back({std::string(block) + ".latency", t.first, {}, 0, 1000000, "latency in cycles"});
      table.push_back({std::string(block) + ".ii", t.second, {}, 1, 1000000, "cycles per unit of work"});
    }
    return true;
  }();
  (void)timing_added;
  static const bool formats_added = [] {
    for (const auto& block : formatted_blocks())
      table.push_back({block + ".format", "default", {}, 0, 0,
                       "number format of the block's datapath (default: pipeline.number_format)", true});
    return true;
  }();
  (void)formats_added;
  return table;
}

const std::vector<std::string>& formatted_blocks() {
  static const std::vector<std::string> blocks = {"normal_interp", "normalize",     "vector_interp",
                                                  "lighting",      "texel_project", "parallax"};
  return blocks;
}

namespace {
const SettingSpec* find_spec(const std::string& key) {
  for (const auto& s : pipeline_settings())
    if (s.key == key) return &s;
  return nullptr;
}

// Flattens nested objects into dotted keys: {"normalize": {"mode": x}} → normalize.mode.
void flatten(const json& j, const std::string& prefix, std::map<std::string, json>& out,
             const std::string& file) {
  for (auto it = j.begin(); it != j.end(); ++it) {
    std::string key = prefix.empty() ? it.key() : prefix + "." + it.key();
    if (it->is_object() && !find_spec(key))
      flatten(*it, key, out, file);
    else if (!out.emplace(key, *it).second)  // both nested and dotted
      throw InputError(file, "pipeline." + key, "the setting is given twice");
  }
}
}  // namespace

PipelineConfig PipelineConfig::from_json(const json& section, const std::string& file) {
  PipelineConfig c;
  if (!section.is_null() && !section.is_object())
    throw InputError(file, "pipeline", "expected an object");
  std::map<std::string, json> given;
  if (section.is_object()) flatten(section, "", given, file);
  for (const auto& [key, value] : given) {
    const SettingSpec* spec = find_spec(key);
    const std::string field = "pipeline." + key;
    if (!spec) {
      std::string known;
      for (const auto& s : pipeline_settings()) known += (known.empty() ? "" : ", ") + s.key;
      throw InputError(file, field, "unknown setting (known: " + known + ")");
    }
    if (spec->fallback.is_string()) {
      if (!value.is_string()) throw InputError(file, field, "expected a string");
      bool ok = spec->choices.empty();
      for (const auto& ch : spec->choices) ok = ok || ch == value.get<std::string>();
      if (!ok) {
        std::string list;
        for (const auto& ch : spec->choices) list += (list.empty() ? "" : ", ") + ch;
        throw InputError(file, field,
                         "unknown value \"" + value.get<std::string>() + "\" (one of: " + list + ")");
      }
      if (spec->number_format && !(key != "number_format" && value == "default")) try {
          NumberFormat::parse(value.get<std::string>());
        } catch (const std::invalid_argument& e) {
          throw InputError(file, field, e.what());
        }
    } else if (spec->fallback.is_boolean()) {
      if (!value.is_boolean()) throw InputError(file, field, "expected true or false");
    } else if (spec->fallback.is_number_integer()) {
      if (!value.is_number_integer()) throw InputError(file, field, "expected an integer");
    } else if (spec->fallback.is_number()) {
      if (!value.is_number()) throw InputError(file, field, "expected a number");
      if (!std::isfinite(value.get<double>())) throw InputError(file, field, "must be finite");
    }
    if (value.is_number() && spec->min < spec->max &&
        (value.get<double>() < spec->min || value.get<double>() > spec->max))
      throw InputError(file, field,
                       "must lie in [" + json(spec->min).dump() + ", " + json(spec->max).dump() + "]");
    c.values_[key] = value;
  }
  for (const auto& s : pipeline_settings())
    if (!c.values_.count(s.key)) c.values_[s.key] = s.fallback;
  for (const auto& [k, v] : c.values_)
    if (v.is_string()) c.strings_[k] = v.get<std::string>();
  return c;
}

const json& PipelineConfig::get(const std::string& key) const {
  auto it = values_.find(key);
  if (it == values_.end()) throw std::logic_error("undeclared pipeline setting: " + key);
  return it->second;
}

double PipelineConfig::number(const std::string& key) const { return get(key).get<double>(); }
int PipelineConfig::integer(const std::string& key) const { return get(key).get<int>(); }
bool PipelineConfig::boolean(const std::string& key) const { return get(key).get<bool>(); }
const std::string& PipelineConfig::string(const std::string& key) const {
  get(key);
  return strings_.at(key);
}

NumberFormat PipelineConfig::format(const std::string& block) const {
  const std::string& name = string(block + ".format");
  return NumberFormat::parse(name == "default" ? string("number_format") : name);
}

json PipelineConfig::resolved() const {
  json out = json::object();
  for (const auto& [k, v] : values_) out[k] = v;
  return out;
}

}  // namespace core
