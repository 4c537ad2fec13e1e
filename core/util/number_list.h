#pragma once
// Comma-separated lists of numbers on the command line ("30,90,3"): the common first step of
// option parsers that then check each value's range and name it in their own messages.
#include <optional>
#include <string>
#include <vector>

namespace irad {

// The fields of `text` split at ',' when every field is a finite decimal number (as strtod
// reads it, without surrounding spaces) and there are between min_count and max_count of them;
// nullopt otherwise (an empty field, a word, "nan", "inf", too few or too many fields).
std::optional<std::vector<double>> parse_number_list(const std::string& text, int min_count,
                                                     int max_count);

} // namespace irad
