#include "shadetlm/core/pipeline_config.hpp"

#include <cmath>
#include <stdexcept>

#include "shadetlm/core/input_error.hpp"
#include "shadetlm/core/nearest.hpp"
#include "shadetlm/core/number_format.hpp"

namespace shadetlm::core {

using json = nlohmann::json;

namespace {
const SettingSpec* find_spec(const std::vector<SettingSpec>& specs, const std::string& key) {
  for (const auto& s : specs)
    if (s.key == key) return &s;
  return nullptr;
}

// Flattens nested objects into dotted keys: {"normalize": {"mode": x}} → normalize.mode.
void flatten(const json& j, const std::string& prefix, std::map<std::string, json>& out,
             const std::string& file) {
  for (auto it = j.begin(); it != j.end(); ++it) {
    std::string key = prefix.empty() ? it.key() : prefix + "." + it.key();
    if (it->is_object() && it->empty())
      throw InputError(file, "pipeline." + key, "expected a value, not an empty object");
    if (it->is_object())  // no setting takes an object: a section of dotted keys
      flatten(*it, key, out, file);
    else if (!out.emplace(key, *it).second)  // both nested and dotted
      throw InputError(file, "pipeline." + key, "the setting is given twice");
  }
}
}  // namespace

PipelineConfig PipelineConfig::from_json(const json& section, const std::string& file) {
  PipelineConfig c;
  c.file_ = file;
  if (!section.is_null() && !section.is_object())
    throw InputError(file, "pipeline", "expected an object");
  if (section.is_object()) flatten(section, "", c.given_, file);
  return c;
}

namespace {
// Throws InputError unless `value` is of the setting's type, among its choices and in
// its range.
void check_value(const SettingSpec& spec, const json& value, const std::string& file) {
  const std::string field = "pipeline." + spec.key;
  if (spec.fallback.is_string()) {
    if (!value.is_string()) throw InputError(file, field, "expected a string");
    bool ok = spec.choices.empty();
    for (const auto& ch : spec.choices) ok = ok || ch == value.get<std::string>();
    if (!ok) {
      std::string list;
      for (const auto& ch : spec.choices) list += (list.empty() ? "" : ", ") + ch;
      const std::string near = nearest_name(value.get<std::string>(), spec.choices);
      throw InputError(file, field, "unknown value \"" + printable(value.get<std::string>()) + "\"" +
                                        (near.empty() ? "" : ": did you mean \"" + near + "\"?") + " (one of: " + list + ")");
    }
    if (spec.number_format && !(spec.key != "number_format" && value == "default")) try {
        NumberFormat::parse(value.get<std::string>());
      } catch (const std::invalid_argument& e) {
        throw InputError(file, field, e.what());
      }
  } else if (spec.fallback.is_boolean()) {
    if (!value.is_boolean()) throw InputError(file, field, "expected true or false");
  } else if (spec.fallback.is_number_integer()) {
    if (!value.is_number_integer()) throw InputError(file, field, "expected an integer");
  } else if (spec.fallback.is_number()) {
    if (!value.is_number()) throw InputError(file, field, "expected a number");
    if (!std::isfinite(value.get<double>())) throw InputError(file, field, "must be finite");
  }
  if (value.is_number() && spec.min < spec.max && (value.get<double>() < spec.min || value.get<double>() > spec.max))
    throw InputError(file, field, "must lie in [" + json(spec.min).dump() + ", " + json(spec.max).dump() + "]");
}
}  // namespace

Settings PipelineConfig::resolve(const std::vector<SettingSpec>& specs) const {
  Settings c;
  for (const auto& [key, value] : given_) {
    const SettingSpec* spec = find_spec(specs, key);
    if (!spec) {  // a typo: the nearest key, else where the keys are listed
      std::vector<std::string> keys;
      for (const auto& s : specs) keys.push_back(s.key);
      const std::string near = nearest_name(key, keys);
      throw InputError(file_, "pipeline." + key,
                       "unknown setting" + (near.empty() ? std::string() : ": did you mean pipeline." + near + "?") +
                           " (docs/configuration.md lists every setting of the pipeline)");
    }
    check_value(*spec, value, file_);
    c.values_[key] = value;
  }
  for (const auto& s : specs)
    if (!c.values_.count(s.key)) c.values_[s.key] = s.fallback;
  for (const auto& [k, v] : c.values_)
    if (v.is_string()) c.strings_[k] = v.get<std::string>();
  return c;
}

const json& Settings::get(const std::string& key) const {
  auto it = values_.find(key);
  if (it == values_.end()) throw std::logic_error("undeclared pipeline setting: " + key);  // a block reads what it declared
  return it->second;
}

double Settings::number(const std::string& key) const { return get(key).get<double>(); }
int Settings::integer(const std::string& key) const { return get(key).get<int>(); }
bool Settings::boolean(const std::string& key) const { return get(key).get<bool>(); }
const std::string& Settings::string(const std::string& key) const {
  get(key);
  return strings_.at(key);
}

json Settings::resolved() const {
  json out = json::object();
  for (const auto& [k, v] : values_) out[k] = v;
  return out;
}

}  // namespace shadetlm::core
