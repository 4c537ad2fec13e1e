#include "core/util/error.h"

namespace irad {

namespace {
std::string join(const std::string& file, const std::string& element, const std::string& message) {
  std::string s;
  if (!file.empty()) s += file + ": ";
  if (!element.empty()) s += element + ": ";
  return s + message;
}
} // namespace

Error::Error(const std::string& file, const std::string& element, const std::string& message)
    : std::runtime_error(join(file, element, message)) {}

} // namespace irad
