#pragma once
// The `pipeline` section of a scene: block configuration as `<block>.<setting>` keys
// (`pipeline.normalize.mode` on the command line). core/ knows no block: a scene keeps
// the settings it was given (PipelineConfig), and the pipeline's declaration, where each
// block declares its own settings (tlm/block.hpp), resolves them into
// Settings: unknown keys and wrong values are rejected there, naming the file and key.
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "shadetlm/core/number_format.hpp"

namespace shadetlm::core {

struct SettingSpec {
  std::string key;             // "normalize.mode" (a block declares "mode": its name goes in front)
  nlohmann::json fallback;     // the default; its type is the setting's type
  std::vector<std::string> choices;  // allowed strings (empty: any of the type)
  double min = 0, max = 0;     // numeric range (when min < max)
  std::string doc;             // one line for docs/configuration.md
  bool number_format = false;  // a string naming a number format (core::NumberFormat)
};

// Every setting with its value: what was given, else its default.
class Settings {
 public:
  double number(const std::string& key) const;
  int integer(const std::string& key) const;
  const std::string& string(const std::string& key) const;
  bool boolean(const std::string& key) const;
  bool has(const std::string& key) const { return values_.count(key) > 0; }

  // Every setting with its resolved value, as a flat JSON object.
  nlohmann::json resolved() const;

 private:
  friend class PipelineConfig;
  const nlohmann::json& get(const std::string& key) const;
  std::map<std::string, nlohmann::json> values_;
  std::map<std::string, std::string> strings_;
};

class PipelineConfig {
 public:
  // Reads the `pipeline` JSON object (nested or dotted keys) of `file`: a setting given
  // twice, or a section that is not an object, is refused here.
  static PipelineConfig from_json(const nlohmann::json& section, const std::string& file);

  // Checks what was given against `specs` (type, choices, range, number formats) and
  // fills in the defaults; throws InputError naming the file and `pipeline.<key>`.
  Settings resolve(const std::vector<SettingSpec>& specs) const;
  // The settings as given, by dotted key.
  const std::map<std::string, nlohmann::json>& given() const { return given_; }

 private:
  std::map<std::string, nlohmann::json> given_;
  std::string file_;
};

}  // namespace shadetlm::core
