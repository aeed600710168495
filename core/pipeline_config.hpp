#pragma once
// The `pipeline` section of a scene: block configuration as `<block>.<setting>` keys
// (`pipeline.normalize.mode` on the command line). Every setting is declared once in
// a table (pipeline_config.cpp) with its type, allowed values and default; unknown
// keys and wrong values are rejected when the scene is read.
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/number_format.hpp"

namespace core {

struct SettingSpec {
  std::string key;             // "normalize.mode"
  nlohmann::json fallback;     // the default; its type is the setting's type
  std::vector<std::string> choices;  // allowed strings (empty: any of the type)
  double min = 0, max = 0;     // numeric range (when min < max)
  std::string doc;             // one line for docs/configuration.md
  bool number_format = false;  // a string naming a number format (core::NumberFormat)
};

// The blocks whose datapaths run in a number format of their own (`<block>.format`).
const std::vector<std::string>& formatted_blocks();

const std::vector<SettingSpec>& pipeline_settings();

class PipelineConfig {
 public:
  // Validates the `pipeline` JSON object (nested or dotted keys) of `file`.
  static PipelineConfig from_json(const nlohmann::json& section, const std::string& file);

  double number(const std::string& key) const;
  int integer(const std::string& key) const;
  const std::string& string(const std::string& key) const;
  bool boolean(const std::string& key) const;
  // The number format of a block of formatted_blocks(): `<block>.format`, or
  // number_format where that is "default".
  NumberFormat format(const std::string& block) const;

  // Every setting with its resolved value, as a flat JSON object.
  nlohmann::json resolved() const;

 private:
  const nlohmann::json& get(const std::string& key) const;
  std::map<std::string, nlohmann::json> values_;
  std::map<std::string, std::string> strings_;
};

}  // namespace core
