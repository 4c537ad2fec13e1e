#pragma once
// Errors carry the file and the element they concern. They are thrown by the libraries and caught
// once, in main, which prints what() on one line and exits with code 1.
#include <stdexcept>
#include <string>

namespace irad {

class Error : public std::runtime_error {
public:
  // what() reads "FILE: ELEMENT: MESSAGE" (parts that are empty are left out).
  Error(const std::string& file, const std::string& element, const std::string& message);
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

} // namespace irad
