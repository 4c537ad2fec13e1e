#include "irad/parts.h"

#include "core/util/error.h"

#include <algorithm>
#include <charconv>
#include <climits>
#include <cstdint>
#include <cstdlib>
#include <fmt/format.h>
#include <fstream>
#include <glm/glm.hpp>
#include <optional>
#include <string_view>

namespace irad {

namespace {

// A non-negative integer with nothing around it, or nullopt.
std::optional<std::uint64_t> parse_count(std::string_view text) {
  std::uint64_t value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

// Task t of k from the Slurm array's environment.
std::pair<std::uint64_t, std::uint64_t> array_task(const char* option) {
  const auto variable = [option](const char* name, bool required) -> std::optional<std::uint64_t> {
    const char* value = std::getenv(name);
    if (value == nullptr && !required) return std::nullopt;
    const auto n = value ? parse_count(value) : std::nullopt;
    if (!n)
      throw Error("", option, fmt::format("auto needs {} (an array job: sbatch --array)", name));
    return n;
  };
  const std::uint64_t id = *variable("SLURM_ARRAY_TASK_ID", true);
  const std::uint64_t count = *variable("SLURM_ARRAY_TASK_COUNT", true);
  const std::uint64_t min = variable("SLURM_ARRAY_TASK_MIN", false).value_or(0);
  if (id < min || id - min >= count || count == 0)
    throw Error("", option,
                fmt::format("auto: task {} is not one of {} tasks from {} (use --array=0-{} "
                            "without a step)",
                            id, count, min, count == 0 ? 0 : count - 1));
  return {id - min, count};
}

std::string range_text(std::uint32_t first, std::uint32_t end) {
  return fmt::format("{}:{}", first, end);
}

const std::string& required(const ExrAttributes& a, const std::string& name,
                            const std::string& file) {
  const auto it = a.find(name);
  if (it == a.end())
    throw Error(file, name, "missing: not a part written by irad render --path-range/--spp-range");
  return it->second;
}

std::uint32_t count_attribute(const ExrAttributes& a, const std::string& name,
                              const std::string& file) {
  const auto n = parse_count(required(a, name, file));
  if (!n || *n > UINT32_MAX) throw Error(file, name, "is not a count");
  return static_cast<std::uint32_t>(*n);
}

// The first entry of two ';'-separated option lists that differs, "NAME=VALUE" each.
std::pair<std::string, std::string> first_difference(const std::string& a, const std::string& b) {
  std::size_t i = 0, j = 0;
  while (i < a.size() || j < b.size()) {
    const std::size_t ea = std::min(a.find(';', i), a.size());
    const std::size_t eb = std::min(b.find(';', j), b.size());
    if (a.compare(i, ea - i, b, j, eb - j) != 0) return {a.substr(i, ea - i), b.substr(j, eb - j)};
    i = ea + 1;
    j = eb + 1;
  }
  return {a, b};
}

// Throws naming `file` unless `part` belongs with `first` (the part of the lowest range).
void check_same(const PartInfo& first, const std::string& first_file, const PartInfo& part,
                const std::string& file) {
  const auto differ = [&](const char* what, const std::string& a, const std::string& b) {
    if (a != b)
      throw Error(file, "",
                  fmt::format("does not belong with {}: other {} ('{}', not '{}')", first_file,
                              what, b, a));
  };
  differ("scene (irad.scene.fnv1a64)", first.scene_hash, part.scene_hash);
  const auto [mine, theirs] = first_difference(first.options, part.options);
  differ("options (irad.options)", mine, theirs);
  differ("irad version", first.version, part.version);
  differ("kind of range", first.kind, part.kind);
  differ("total", std::to_string(first.total), std::to_string(part.total));
}

} // namespace

std::pair<std::uint32_t, std::uint32_t> parse_part_range(const std::string& text,
                                                         std::uint32_t total, const char* option) {
  std::uint64_t first = 0, end = 0;
  if (text == "auto") {
    const auto [t, k] = array_task(option);
    first = t * total / k;
    end = (t + 1) * total / k;
  } else {
    const std::size_t colon = text.find(':');
    const auto a = parse_count(std::string_view(text).substr(0, colon));
    const auto b = colon == std::string::npos
                       ? std::nullopt
                       : parse_count(std::string_view(text).substr(colon + 1));
    if (!a || !b) throw Error("", option, fmt::format("'{}' is not A:B or auto", text));
    first = *a;
    end = *b;
  }
  if (first >= end || end > total)
    throw Error("", option,
                fmt::format("{}:{} is not a non-empty range within 0:{}", first, end, total));
  return {static_cast<std::uint32_t>(first), static_cast<std::uint32_t>(end)};
}

// FNV-1a 64: h = (h xor byte) * 0x100000001b3 from 0xcbf29ce484222325.
std::string file_hash(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path.string(), "", "cannot read");
  std::uint64_t h = 0xcbf29ce484222325ull;
  char buffer[1 << 16];
  while (in) {
    in.read(buffer, sizeof buffer);
    for (std::streamsize i = 0; i < in.gcount(); ++i)
      h = (h ^ static_cast<unsigned char>(buffer[i])) * 0x100000001b3ull;
  }
  if (in.bad()) throw Error(path.string(), "", "cannot read");
  return fmt::format("{:016x}", h);
}

const char* irad_version() {
  return IRAD_VERSION;
}

ExrAttributes part_attributes(const PartInfo& part) {
  return {{"irad.part.kind", part.kind},
          {"irad.part.total", std::to_string(part.total)},
          {"irad.part.range", range_text(part.first, part.end)},
          {"irad.part.merge", "sum: each part holds its range's light with the full render's "
                              "weights; the part from 0 holds the emitters and background"},
          {"irad.scene.file", part.scene_file},
          {"irad.scene.fnv1a64", part.scene_hash},
          {"irad.options", part.options},
          {"irad.version", part.version}};
}

PartInfo part_info(const ExrAttributes& a, const std::string& file) {
  PartInfo p;
  p.kind = required(a, "irad.part.kind", file);
  if (p.kind != "paths" && p.kind != "spp")
    throw Error(file, "irad.part.kind", "'" + p.kind + "' is not paths or spp");
  p.total = count_attribute(a, "irad.part.total", file);
  const std::string& range = required(a, "irad.part.range", file);
  const std::size_t colon = range.find(':');
  const auto first = parse_count(std::string_view(range).substr(0, colon));
  const auto end = colon == std::string::npos
                       ? std::nullopt
                       : parse_count(std::string_view(range).substr(colon + 1));
  if (!first || !end || *first >= *end || *end > p.total)
    throw Error(file, "irad.part.range", "'" + range + "' is not a range within the total");
  p.first = static_cast<std::uint32_t>(*first);
  p.end = static_cast<std::uint32_t>(*end);
  p.scene_file = required(a, "irad.scene.file", file);
  p.scene_hash = required(a, "irad.scene.fnv1a64", file);
  p.options = required(a, "irad.options", file);
  p.version = required(a, "irad.version", file);
  return p;
}

MergedImage merge_parts(const std::vector<std::string>& files) {
  struct Part {
    std::string file;
    PartInfo info;
    Image image;
  };
  std::vector<Part> parts;
  for (const std::string& f : files) {
    ExrAttributes attributes;
    Image image = read_exr(f, &attributes);
    parts.push_back({f, part_info(attributes, f), std::move(image)});
  }
  if (parts.empty()) throw Error("", "PART.exr", "no parts given");
  std::stable_sort(parts.begin(), parts.end(),
                   [](const Part& a, const Part& b) { return a.info.first < b.info.first; });
  const Part& head = parts.front();
  std::uint32_t covered = 0; // the parts so far cover 0..covered-1
  for (const Part& p : parts) {
    check_same(head.info, head.file, p.info, p.file);
    if (p.image.width() != head.image.width() || p.image.height() != head.image.height())
      throw Error(p.file, "",
                  fmt::format("is {}x{}, {} is {}x{}", p.image.width(), p.image.height(), head.file,
                              head.image.width(), head.image.height()));
    if (p.info.first < covered)
      throw Error(p.file, "irad.part.range",
                  fmt::format("{}:{} overlaps the ranges before it (0:{})", p.info.first,
                              p.info.end, covered));
    if (p.info.first > covered)
      throw Error(p.file, "irad.part.range",
                  fmt::format("{}:{} leaves {}:{} missing", p.info.first, p.info.end, covered,
                              p.info.first));
    covered = p.info.end;
  }
  if (covered != head.info.total)
    throw Error(parts.back().file, "irad.part.range",
                fmt::format("the parts end at {}, leaving {}:{} missing", covered, covered,
                            head.info.total));
  std::vector<glm::dvec4> sum(head.image.pixels().size(), glm::dvec4(0.0));
  for (const Part& p : parts)
    for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += glm::dvec4(p.image.pixels()[i]);
  MergedImage merged{Image(head.image.width(), head.image.height()), head.info};
  for (std::size_t i = 0; i < sum.size(); ++i) merged.image.pixels()[i] = glm::vec4(sum[i]);
  merged.info.first = 0;
  merged.info.end = head.info.total;
  return merged;
}

} // namespace irad
