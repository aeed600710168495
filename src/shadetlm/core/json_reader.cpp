#include "shadetlm/core/json_reader.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include "shadetlm/core/nearest.hpp"

namespace shadetlm::core {

namespace {
std::string type_name(const json& v) {
  if (v.is_number()) return "a number";
  if (v.is_string()) return "the string \"" + printable(v.get<std::string>()) + "\"";
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  if (v.is_null()) return "null";
  if (v.is_array()) return "an array";
  return "an object";
}
}  // namespace

JsonReader::JsonReader(const json& value, std::string file, std::string path)
    : value_(value), file_(std::move(file)), path_(std::move(path)) {
  if (!value_.is_object())
    throw InputError(file_, path_, "expected an object, got " + type_name(value_));
}

std::string JsonReader::field(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

void JsonReader::fail(const std::string& key, const std::string& what) const {
  throw InputError(file_, key.empty() ? path_ : field(key), what);
}

bool JsonReader::has(const std::string& key) const { return value_.contains(key); }

const json* JsonReader::find(const std::string& key) {
  read_.insert(key);
  auto it = value_.find(key);
  return it == value_.end() ? nullptr : &*it;
}

const json& JsonReader::raw(const std::string& key) {
  const json* v = find(key);
  if (!v) fail(key, "missing");
  return *v;
}

double JsonReader::number(const std::string& key, std::optional<double> fallback, double min,
                          double max) {
  const json* v = find(key);
  if (!v) {
    if (fallback) return *fallback;
    fail(key, "missing (a number is required)");
  }
  if (!v->is_number()) fail(key, "expected a number, got " + type_name(*v));
  double x = v->get<double>();
  if (!std::isfinite(x)) fail(key, "must be finite");
  if (x < min || x > max) {
    std::ostringstream s;
    s << "must lie in [" << min << ", " << max << "], got " << x;
    fail(key, s.str());
  }
  return x;
}

int JsonReader::integer(const std::string& key, std::optional<int> fallback, int min, int max) {
  const json* v = find(key);
  if (!v) {
    if (fallback) return *fallback;
    fail(key, "missing (an integer is required)");
  }
  if (!v->is_number_integer()) fail(key, "expected an integer, got " + type_name(*v));
  // (an unsigned beyond long long's range reads as negative: compared as given)
  const long long x = v->is_number_unsigned() && v->get<unsigned long long>() > uint64_t(max) ? max + 1LL
                                                                                               : v->get<long long>();
  if (x < min || x > max)
    fail(key, "must lie in [" + std::to_string(min) + ", " + std::to_string(max) + "], got " + v->dump());
  return static_cast<int>(x);
}

bool JsonReader::boolean(const std::string& key, std::optional<bool> fallback) {
  const json* v = find(key);
  if (!v) {
    if (fallback) return *fallback;
    fail(key, "missing (true or false is required)");
  }
  if (!v->is_boolean()) fail(key, "expected true or false, got " + type_name(*v));
  return v->get<bool>();
}

std::string JsonReader::string(const std::string& key, std::optional<std::string> fallback) {
  const json* v = find(key);
  if (!v) {
    if (fallback) return *fallback;
    fail(key, "missing (a string is required)");
  }
  if (!v->is_string()) fail(key, "expected a string, got " + type_name(*v));
  return v->get<std::string>();
}

std::string JsonReader::choice(const std::string& key, std::optional<std::string> fallback,
                               const std::vector<std::string>& allowed) {
  std::string s = string(key, fallback);
  for (const auto& a : allowed)
    if (a == s) return s;
  std::string list;
  for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
  const std::string near = nearest_name(s, allowed);
  fail(key, "unknown value \"" + printable(s) + "\"" + (near.empty() ? "" : ": did you mean \"" + near + "\"?") +
                " (one of: " + list + ")");
}

std::vector<double> JsonReader::numbers(const std::string& key, size_t count) {
  const json& v = *find(key);
  if (!v.is_array() || v.size() != count)
    fail(key, "expected an array of " + std::to_string(count) + " numbers, got " + type_name(v));
  std::vector<double> out;
  for (size_t i = 0; i < count; ++i) {
    const std::string f = key + "." + std::to_string(i);
    if (!v[i].is_number()) fail(f, "expected a number, got " + type_name(v[i]));
    double x = v[i].get<double>();
    if (!std::isfinite(x)) fail(f, "must be finite");
    out.push_back(x);
  }
  return out;
}

glm::dvec2 JsonReader::vec2(const std::string& key, std::optional<glm::dvec2> fallback) {
  if (!has(key)) {
    read_.insert(key);
    if (fallback) return *fallback;
    fail(key, "missing (an array of 2 numbers is required)");
  }
  auto n = numbers(key, 2);
  return {n[0], n[1]};
}

glm::dvec3 JsonReader::vec3(const std::string& key, std::optional<glm::dvec3> fallback) {
  if (!has(key)) {
    read_.insert(key);
    if (fallback) return *fallback;
    fail(key, "missing (an array of 3 numbers is required)");
  }
  auto n = numbers(key, 3);
  return {n[0], n[1], n[2]};
}

std::vector<glm::dvec3> JsonReader::vec3_list(const std::string& key, size_t count) {
  const json& v = raw(key);
  if (!v.is_array() || v.size() != count)
    fail(key, "expected an array of " + std::to_string(count) + " arrays of 3 numbers");
  std::vector<glm::dvec3> out;
  for (size_t i = 0; i < count; ++i) {
    const json& e = v[i];
    const std::string f = key + "." + std::to_string(i);
    if (!e.is_array() || e.size() != 3) fail(f, "expected an array of 3 numbers, got " + type_name(e));
    glm::dvec3 c;
    for (int k = 0; k < 3; ++k) {
      if (!e[k].is_number()) fail(f + "." + std::to_string(k), "expected a number, got " + type_name(e[k]));
      c[k] = e[k].get<double>();
      if (!std::isfinite(c[k])) fail(f + "." + std::to_string(k), "must be finite");
    }
    out.push_back(c);
  }
  return out;
}

glm::ivec2 JsonReader::ivec2(const std::string& key, std::optional<glm::ivec2> fallback, int min,
                             int max) {
  const json* v = find(key);
  if (!v) {
    if (fallback) return *fallback;
    fail(key, "missing (an array of 2 integers is required)");
  }
  if (!v->is_array() || v->size() != 2)
    fail(key, "expected an array of 2 integers, got " + type_name(*v));
  glm::ivec2 out;
  for (int i = 0; i < 2; ++i) {
    const json& e = (*v)[i];
    const std::string f = key + "." + std::to_string(i);
    if (!e.is_number_integer()) fail(f, "expected an integer, got " + type_name(e));
    const long long x = e.is_number_unsigned() && e.get<unsigned long long>() > uint64_t(max) ? max + 1LL
                                                                                               : e.get<long long>();
    if (x < min || x > max)
      fail(f, "must lie in [" + std::to_string(min) + ", " + std::to_string(max) + "], got " + e.dump());
    out[i] = static_cast<int>(x);
  }
  return out;
}

JsonReader JsonReader::object(const std::string& key) {
  return JsonReader(raw(key), file_, field(key));
}

std::vector<std::pair<const json*, std::string>> JsonReader::array(const std::string& key) {
  const json& v = raw(key);
  if (!v.is_array()) fail(key, "expected an array, got " + type_name(v));
  std::vector<std::pair<const json*, std::string>> out;
  for (size_t i = 0; i < v.size(); ++i) out.emplace_back(&v[i], field(key) + "." + std::to_string(i));
  return out;
}

void JsonReader::finish() const {
  for (auto it = value_.begin(); it != value_.end(); ++it)
    if (!read_.count(it.key())) {
      std::string known;
      for (const auto& k : read_) known += (known.empty() ? "" : ", ") + k;
      const std::string near = nearest_name(it.key(), std::vector<std::string>(read_.begin(), read_.end()));
      throw InputError(file_, field(printable(it.key())),
                       "unknown key" + (near.empty() ? std::string() : ": did you mean " + near + "?") +
                           (known.empty() ? std::string() : " (known here: " + known + ")"));
    }
}

json parse_json_text(const std::string& text, const std::string& file) {
  // nlohmann keeps the last of repeated keys; a scene must not say one thing twice. The
  // levels open at the parser's position: an object's keys so far, an array's element.
  struct Level {
    bool array = false;
    std::set<std::string> keys;
    std::string key;  // the object's current member
    long index = -1;  // the array's current element
  };
  std::vector<Level> levels;
  std::string duplicate;  // its full path, "objects.0.radius"
  auto path_to = [&](const std::string& key) {
    std::string p;
    for (size_t i = 0; i + 1 < levels.size(); ++i)
      p += (p.empty() ? "" : ".") + (levels[i].array ? std::to_string(levels[i].index) : levels[i].key);
    return p + (p.empty() ? "" : ".") + key;
  };
  // Copying or destroying a JSON value recurses once per level: a document nested
  // thousands deep would overflow the stack. Scenes need a handful of levels.
  constexpr int kMaxDepth = 64;
  auto check = [&](int depth, json::parse_event_t event, json& parsed) {
    if (depth > kMaxDepth)
      throw InputError(file, "", "nested deeper than " + std::to_string(kMaxDepth) + " levels");
    const bool starts = event == json::parse_event_t::object_start || event == json::parse_event_t::array_start;
    if ((starts || event == json::parse_event_t::value) && !levels.empty() && levels.back().array &&
        !(event == json::parse_event_t::value && (parsed.is_object() || parsed.is_array())))
      ++levels.back().index;  // an array's next element begins (a finished compound one is no new element)
    if (starts) {
      levels.emplace_back();
      levels.back().array = event == json::parse_event_t::array_start;
    } else if (event == json::parse_event_t::object_end || event == json::parse_event_t::array_end) {
      levels.pop_back();
    } else if (event == json::parse_event_t::key && !levels.empty()) {
      Level& object = levels.back();
      object.key = parsed.get<std::string>();
      if (!object.keys.insert(object.key).second && duplicate.empty()) duplicate = path_to(printable(object.key));
    }
    return true;
  };
  // Where the parser is: the path of the member or element it reads (for its errors).
  auto here = [&] {
    if (levels.empty()) return std::string();
    Level& last = levels.back();
    return path_to(last.array ? std::to_string(last.index + 1) : printable(last.key));
  };
  const size_t nul = text.find('\0');
  if (nul != std::string::npos)
    throw InputError(file, "", "holds a NUL byte at byte " + std::to_string(nul) + " (not a JSON text)");
  try {
    json doc = json::parse(text, check);
    if (!duplicate.empty()) throw InputError(file, duplicate, "the key is given twice in one object");
    return doc;
  } catch (const json::parse_error& e) {
    // Turn the byte offset into a line and a column a user can jump to.
    size_t line = 1, col = 1;
    for (size_t i = 0; i + 1 < e.byte && i < text.size(); ++i) {
      if (text[i] == '\n') { ++line; col = 1; } else { ++col; }
    }
    std::string what = e.what();
    auto pos = what.find("syntax error");
    throw InputError(file, "line " + std::to_string(line) + ", column " + std::to_string(col),
                     "invalid JSON: " + (pos == std::string::npos ? what : what.substr(pos)));
  } catch (const json::exception& e) {  // e.g. a number literal too large for a double
    std::string what = e.what();
    auto pos = what.find("] ");
    throw InputError(file, here(), "invalid JSON: " + (pos == std::string::npos ? what : what.substr(pos + 2)));
  }
}

json parse_json_file(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file, "", "cannot open the file");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_json_text(ss.str(), file);
}

}  // namespace shadetlm::core
