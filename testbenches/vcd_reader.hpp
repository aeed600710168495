#pragma once
// A small reader of the VCD files SystemC writes, for the tests: the declarations
// (full names with their scopes, as GTKWave shows them) and every value change.
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace test {

struct Vcd {
  struct Change {
    uint64_t time;
    std::string id;
    double value;  // reals as read; vectors and bits as integers
  };
  std::map<std::string, std::string> name_of;  // id → "shadetlm.raster.x[31:0]"
  std::map<std::string, std::string> id_of;    // full name → id
  std::vector<Change> changes;                 // in file order
  bool header_ok = false;                      // $timescale, $scope, $var, $enddefinitions seen
  bool times_ok = true;                        // timestamps never decrease
  std::string problem;
};

inline Vcd read_vcd(const std::string& path) {
  Vcd v;
  std::ifstream in(path);
  std::string token, scope;
  std::vector<std::string> scopes;
  bool timescale = false, var = false, enddefs = false;
  uint64_t now = 0;
  bool any_time = false;
  while (in >> token) {
    if (!enddefs) {
      if (token == "$timescale") timescale = true;
      if (token == "$scope") {
        std::string kind, name;
        in >> kind >> name;
        scopes.push_back(name);
      } else if (token == "$upscope") {
        if (!scopes.empty()) scopes.pop_back();
      } else if (token == "$var") {
        std::string type, width, id, name, word;
        in >> type >> width >> id >> name;
        std::string full;
        for (const auto& s : scopes) full += s + ".";
        full += name;
        while (in >> word && word != "$end") full += word;  // "[31:0]"
        v.name_of[id] = full;
        v.id_of[full] = id;
        var = true;
      } else if (token == "$enddefinitions") {
        enddefs = true;
      }
      continue;
    }
    if (token == "$comment") {  // free text up to $end
      while (in >> token && token != "$end") {}
      continue;
    }
    if (token[0] == '$') continue;  // $dumpvars, $end
    if (token[0] == '#') {
      const uint64_t t = std::stoull(token.substr(1));
      if (any_time && t < now) v.times_ok = false;
      now = t;
      any_time = true;
    } else if (token[0] == 'r' || token[0] == 'b') {  // real or vector: value then id
      std::string id;
      in >> id;
      // An unknown vector (bx: not valid) reads as NaN.
      const double value = token[0] == 'r'      ? std::stod(token.substr(1))
                           : token == "bx"      ? std::numeric_limits<double>::quiet_NaN()
                                                : double(std::stoull(token.substr(1), nullptr, 2));
      v.changes.push_back({now, id, value});
    } else {  // a bit: value and id joined
      v.changes.push_back({now, token.substr(1), double(token[0] == '1')});
    }
  }
  v.header_ok = timescale && var && enddefs;
  return v;
}

}  // namespace test
