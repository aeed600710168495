#pragma once
// The io component (shadetlm::io), all of this header.
// A strict view of one JSON object of an input file: every read names the field in
// its error, numbers must be finite, and finish() rejects keys nobody read (a typo in
// a key must not silently fall back to a default).
#include <initializer_list>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "shadetlm/core/input_error.hpp"

namespace shadetlm::core {

using json = nlohmann::json;

class JsonReader {
 public:
  // `path` is the dotted field path of `value` inside `file` ("" for the root).
  JsonReader(const json& value, std::string file, std::string path);

  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }
  std::string field(const std::string& key) const;  // path of a member
  [[noreturn]] void fail(const std::string& key, const std::string& what) const;

  bool has(const std::string& key) const;
  const json& raw(const std::string& key);  // marks the key as read

  double number(const std::string& key, std::optional<double> fallback = std::nullopt,
                double min = -1e300, double max = 1e300);
  int integer(const std::string& key, std::optional<int> fallback, int min, int max);
  bool boolean(const std::string& key, std::optional<bool> fallback = std::nullopt);
  std::string string(const std::string& key,
                     std::optional<std::string> fallback = std::nullopt);
  std::string choice(const std::string& key, std::optional<std::string> fallback,
                     const std::vector<std::string>& allowed);
  glm::dvec2 vec2(const std::string& key, std::optional<glm::dvec2> fallback = std::nullopt);
  glm::dvec3 vec3(const std::string& key, std::optional<glm::dvec3> fallback = std::nullopt);
  // An array of exactly `count` 3-vectors, e.g. a pair of colours.
  std::vector<glm::dvec3> vec3_list(const std::string& key, size_t count);
  glm::ivec2 ivec2(const std::string& key, std::optional<glm::ivec2> fallback, int min, int max);

  // A member that is itself an object, as a reader of its own.
  JsonReader object(const std::string& key);
  // Members of an array, each as (value, field path).
  std::vector<std::pair<const json*, std::string>> array(const std::string& key);

  // Throws for the first key that was never read.
  void finish() const;

 private:
  const json* find(const std::string& key);
  std::vector<double> numbers(const std::string& key, size_t count);

  const json& value_;
  std::string file_, path_;
  std::set<std::string> read_;
};

// Reads a JSON file; a syntax error names the file, the line and the column.
json parse_json_file(const std::string& file);
json parse_json_text(const std::string& text, const std::string& file);

}  // namespace shadetlm::core
