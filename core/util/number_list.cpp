#include "core/util/number_list.h"

#include <charconv>
#include <cmath>
#include <string_view>

namespace irad {

namespace {

// One field as a finite number; from_chars takes no leading spaces or '+' and ignores the locale.
std::optional<double> parse_field(std::string_view field) {
  double value = 0.0;
  const char* end = field.data() + field.size();
  const auto [ptr, ec] = std::from_chars(field.data(), end, value);
  if (ec != std::errc() || ptr != end || !std::isfinite(value)) return std::nullopt;
  return value;
}

} // namespace

std::optional<std::vector<double>> parse_number_list(const std::string& text, int min_count,
                                                     int max_count) {
  std::vector<double> values;
  std::string_view rest = text;
  while (true) {
    const std::size_t comma = rest.find(',');
    const std::optional<double> value = parse_field(rest.substr(0, comma));
    if (!value) return std::nullopt;
    values.push_back(*value);
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  const int count = static_cast<int>(values.size());
  if (count < min_count || count > max_count) return std::nullopt;
  return values;
}

} // namespace irad
