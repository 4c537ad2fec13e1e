#include "conformance_probe.h"

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <vector>

namespace irad::test {
namespace {

using json = nlohmann::ordered_json; // keeps the file's key order

// SAX pass that accepts only what json::parse followed by dump() reproduces: no duplicate keys
// (the DOM keeps one), no integer too large for 64 bits (it would become a double), no number
// that overflows to infinity (dump() writes null).
class ExactJson : public nlohmann::json_sax<json> {
public:
  bool null() override { return true; }
  bool boolean(bool) override { return true; }
  bool number_integer(number_integer_t) override { return true; }
  bool number_unsigned(number_unsigned_t) override { return true; }
  bool number_float(number_float_t value, const string_t& text) override {
    return std::isfinite(value) && text.find_first_of(".eE") != string_t::npos;
  }
  bool string(string_t&) override { return true; }
  bool binary(binary_t&) override { return true; }
  bool start_object(std::size_t) override {
    keys_.emplace_back();
    return true;
  }
  bool key(string_t& name) override { return keys_.back().insert(name).second; }
  bool end_object() override {
    keys_.pop_back();
    return true;
  }
  bool start_array(std::size_t) override { return true; }
  bool end_array() override { return true; }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override {
    return false;
  }

private:
  std::vector<std::set<std::string>> keys_;
};

bool parses_exactly(const std::string& text) {
  if (text.rfind("\xEF\xBB\xBF", 0) == 0) return false; // json::parse would skip the BOM
  ExactJson sax;
  return json::sax_parse(text, &sax, json::input_format_t::json, true);
}

std::string base64(const std::vector<std::uint8_t>& in) {
  static constexpr char kDigits[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < in.size(); i += 3) {
    std::uint32_t v = std::uint32_t(in[i]) << 16;
    if (i + 1 < in.size()) v |= std::uint32_t(in[i + 1]) << 8;
    if (i + 2 < in.size()) v |= in[i + 2];
    out += kDigits[(v >> 18) & 63];
    out += kDigits[(v >> 12) & 63];
    out += i + 1 < in.size() ? kDigits[(v >> 6) & 63] : '=';
    out += i + 2 < in.size() ? kDigits[v & 63] : '=';
  }
  return out;
}

// The triangle's 3 x VEC3 float positions, little-endian.
constexpr std::array<float, 9> kPositions = {0, 0, 0, 1, 0, 0, 0, 1, 0};

std::string positions_uri() {
  std::vector<std::uint8_t> bytes;
  for (float f : kPositions) {
    const auto bits = std::bit_cast<std::uint32_t>(f);
    for (int b = 0; b < 4; ++b) bytes.push_back(static_cast<std::uint8_t>(bits >> (8 * b)));
  }
  return "data:application/octet-stream;base64," + base64(bytes);
}

// Makes doc[key] an array to append to (created when absent); false when it is present but not
// an array, or empty. Adding a key may move doc's other members (ordered_json is a vector): no
// pointer into doc is kept across calls.
bool appendable(json& doc, const char* key) {
  if (!doc.contains(key)) {
    doc[key] = json::array();
    return true;
  }
  return doc[key].is_array() && !doc[key].empty();
}

// The default scene (`scene`, else 0), its nodes array made appendable; nullopt (no probe) when
// the file's scene structure does not allow it. -1: no scenes (the node is a root anyway).
std::optional<std::int64_t> default_scene(json& doc) {
  if (!doc.contains("scenes")) return -1;
  if (!appendable(doc, "scenes")) return std::nullopt;
  std::size_t index = 0;
  if (doc.contains("scene")) {
    const json& s = doc["scene"];
    if (!s.is_number_unsigned() || s.get<std::uint64_t>() >= doc["scenes"].size())
      return std::nullopt;
    index = s.get<std::size_t>();
  }
  json& scene = doc["scenes"][index];
  if (!scene.is_object() || !appendable(scene, "nodes")) return std::nullopt;
  return static_cast<std::int64_t>(index);
}

// The top-level array each reference key indexes ("attributes" and "targets": their members).
const std::map<std::string, std::string>& reference_keys() {
  static const std::map<std::string, std::string> kKeys = {
      {"buffer", "buffers"},     {"bufferView", "bufferViews"},
      {"indices", "accessors"},  {"attributes", "accessors"},
      {"targets", "accessors"},  {"inverseBindMatrices", "accessors"},
      {"input", "accessors"},    {"output", "accessors"},
      {"material", "materials"}, {"mesh", "meshes"},
      {"children", "nodes"},     {"skeleton", "nodes"},
      {"joints", "nodes"},       {"node", "nodes"},
      {"nodes", "nodes"}};
  return kKeys;
}

// True when some integer under a reference key (or an element of an array under it) equals the
// current size of the array it indexes: the probe's new element would resolve a dangling index.
bool resolves_dangling(const json& value, const std::string& key, const json& doc) {
  if (value.is_number_integer()) {
    const auto it = reference_keys().find(key);
    if (it == reference_keys().end()) return false;
    if (!doc.contains(it->second)) return value.get<std::int64_t>() == 0; // created by the probe
    const json& target = doc[it->second];
    return target.is_array() && value.get<std::int64_t>() == std::int64_t(target.size());
  }
  if (value.is_array()) {
    for (const json& e : value)
      if (resolves_dangling(e, key, doc)) return true;
  }
  if (value.is_object()) {
    const bool members_are_refs = key == "attributes" || key == "targets";
    for (const auto& [k, v] : value.items())
      if (resolves_dangling(v, members_are_refs ? key : k, doc)) return true;
  }
  return false;
}

std::size_t append(json& array, json value) {
  array.push_back(std::move(value));
  return array.size() - 1;
}

} // namespace

std::optional<std::string> probe_gltf_json(const std::string& text) {
  if (!parses_exactly(text)) return std::nullopt;
  json doc = json::parse(text);
  if (!doc.is_object() || resolves_dangling(doc, "", doc)) return std::nullopt;
  const std::optional<std::int64_t> scene = default_scene(doc);
  if (!scene) return std::nullopt;
  for (const char* key : {"buffers", "bufferViews", "accessors", "materials", "meshes", "nodes"})
    if (!appendable(doc, key)) return std::nullopt;

  const std::size_t bytes = kPositions.size() * sizeof(float);
  const auto buffer = append(doc["buffers"], {{"byteLength", bytes}, {"uri", positions_uri()}});
  const auto view = append(doc["bufferViews"], {{"buffer", buffer}, {"byteLength", bytes}});
  const auto accessor = append(doc["accessors"], {{"bufferView", view},
                                                  {"componentType", 5126},
                                                  {"count", 3},
                                                  {"type", "VEC3"},
                                                  {"min", {0.0, 0.0, 0.0}},
                                                  {"max", {1.0, 1.0, 0.0}}});
  const auto material =
      append(doc["materials"], {{"emissiveFactor", {1.0, 1.0, 1.0}}, {"doubleSided", true}});
  const json primitive = {{"attributes", {{"POSITION", accessor}}}, {"material", material}};
  const auto mesh = append(doc["meshes"], {{"primitives", json::array({primitive})}});
  const auto node = append(doc["nodes"], {{"mesh", mesh}});
  if (*scene >= 0) doc["scenes"][static_cast<std::size_t>(*scene)]["nodes"].push_back(node);
  return doc.dump();
}

namespace {

std::uint32_t u32_at(const std::string& b, std::size_t at) {
  std::uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(b[at + i]);
  return v;
}

void put_u32(std::string& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out += static_cast<char>((v >> (8 * i)) & 0xff);
}

constexpr std::uint32_t kJsonChunk = 0x4E4F534A; // "JSON"

// True when the chunks from offset 12 tile [12, length) exactly, each 4-byte aligned.
bool chunks_tile(const std::string& b, std::size_t length) {
  std::size_t at = 12;
  while (at < length) {
    if (length - at < 8) return false;
    const std::uint64_t size = u32_at(b, at);
    if (size % 4 != 0 || size > length - at - 8) return false;
    at += 8 + size;
  }
  return true;
}

} // namespace

std::optional<std::string> probe_glb(const std::string& b) {
  if (b.size() < 20 || b.compare(0, 4, "glTF") != 0 || u32_at(b, 4) != 2) return std::nullopt;
  const std::size_t length = u32_at(b, 8);
  if (length > b.size() || length < 20 || !chunks_tile(b, length)) return std::nullopt;
  if (u32_at(b, 16) != kJsonChunk) return std::nullopt;
  const std::size_t json_size = u32_at(b, 12);
  const auto json_text = probe_gltf_json(b.substr(20, json_size));
  if (!json_text) return std::nullopt;

  std::string chunk = *json_text;
  while (chunk.size() % 4 != 0) chunk += ' ';
  const std::string rest = b.substr(20 + json_size, length - 20 - json_size);
  std::string out = "glTF";
  put_u32(out, 2);
  put_u32(out, static_cast<std::uint32_t>(12 + 8 + chunk.size() + rest.size()));
  put_u32(out, static_cast<std::uint32_t>(chunk.size()));
  put_u32(out, kJsonChunk);
  out += chunk + rest + b.substr(length); // bytes after the header's length stay after it
  return out;
}

} // namespace irad::test
