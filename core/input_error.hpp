#pragma once
// Bad input — a scene, a texture, a mesh, a frame — reported with the file and the
// field it came from, so that a user can find and fix it.
#include <stdexcept>
#include <string>

namespace shadetlm::core {

class InputError : public std::runtime_error {
 public:
  InputError(const std::string& file, const std::string& field, const std::string& what)
      : std::runtime_error(compose(file, field, what)), file_(file), field_(field) {}

  const std::string& file() const { return file_; }
  const std::string& field() const { return field_; }

 private:
  static std::string compose(const std::string& file, const std::string& field,
                             const std::string& what) {
    std::string s = file.empty() ? std::string("<input>") : file;
    if (!field.empty()) s += ": " + field;
    return s + ": " + what;
  }
  std::string file_, field_;
};

}  // namespace shadetlm::core
