// Bad user input: one error type that names the file, the JSON Pointer, what
// was expected and what was found (docs/reliability.md). The CLI maps it to exit code 2.
#pragma once

#include <stdexcept>
#include <string>

namespace pronk::io {

class InputError : public std::runtime_error {
 public:
  InputError(std::string file, std::string pointer, std::string expected, std::string found);
  const std::string& file() const { return file_; }
  const std::string& pointer() const { return pointer_; }
  const std::string& expected() const { return expected_; }
  const std::string& found() const { return found_; }

 private:
  std::string file_, pointer_, expected_, found_;
};

}  // namespace pronk::io
