// meshopt_glb IN.glb OUT.glb: the same scene with every accessor's buffer view compressed by
// EXT_meshopt_compression (vertex attributes: ATTRIBUTES, no filter; indices: TRIANGLES), through
// meshoptimizer's own encoders. Buffer 0 holds the compressed streams and the views that are no
// accessor's (images) as they were; buffer 1 is the fallback buffer (no data). For the
// EXT_meshopt_compression variant of scripts/make_large_glb.py's file (irad bench --load):
//   cmake --build build --target irad_meshopt_glb
//   build/bin/irad_meshopt_glb build/large_2m.glb build/large_2m_meshopt.glb
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <meshoptimizer.h>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

using json = nlohmann::json;
using Bytes = std::vector<unsigned char>;

namespace {

std::uint32_t le32(const unsigned char* p) {
  return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 |
         std::uint32_t(p[3]) << 24;
}
void put32(Bytes& b, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) b.push_back(static_cast<unsigned char>(v >> (8 * i)));
}
void align4(Bytes& b, unsigned char pad = 0) {
  while (b.size() % 4) b.push_back(pad);
}
std::size_t component_size(int type) {
  switch (type) {
  case 5120:
  case 5121:
    return 1;
  case 5122:
  case 5123:
    return 2;
  default:
    return 4;
  }
}
std::size_t components(const std::string& type) {
  if (type == "SCALAR") return 1;
  if (type == "VEC2") return 2;
  if (type == "VEC3") return 3;
  if (type == "VEC4") return 4;
  if (type == "MAT4") return 16;
  throw std::runtime_error("accessor type " + type);
}

} // namespace

int main(int argc, char** argv) try {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s IN.glb OUT.glb\n", argv[0]);
    return 2;
  }
  std::ifstream in(argv[1], std::ios::binary);
  const Bytes file{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (file.size() < 28 || std::memcmp(file.data(), "glTF", 4) != 0)
    throw std::runtime_error("not a GLB");
  const std::uint32_t json_length = le32(&file[12]);
  json doc = json::parse(file.begin() + 20, file.begin() + 20 + json_length);
  const std::size_t bin_at = 20 + json_length;
  const std::uint32_t bin_length = le32(&file[bin_at]);
  const unsigned char* bin = &file[bin_at + 8];

  // The accessor of each view (one per view in the files this is for).
  std::vector<const json*> accessor_of(doc["bufferViews"].size(), nullptr);
  for (const json& a : doc["accessors"])
    if (a.contains("bufferView")) accessor_of.at(a["bufferView"].get<std::size_t>()) = &a;
  std::set<std::size_t> index_views;
  for (const json& m : doc["meshes"])
    for (const json& p : m["primitives"])
      if (p.contains("indices"))
        index_views.insert(
            doc["accessors"][p["indices"].get<std::size_t>()]["bufferView"].get<std::size_t>());

  Bytes out;
  std::size_t raw = 0, packed = 0;
  for (std::size_t v = 0; v < doc["bufferViews"].size(); ++v) {
    json& view = doc["bufferViews"][v];
    const std::size_t offset = view.value("byteOffset", 0u), length = view["byteLength"];
    const unsigned char* data = bin + offset;
    align4(out);
    const json* a = accessor_of[v];
    if (!a) { // not an accessor's (an image): stays as it is, in buffer 0
      view["byteOffset"] = out.size();
      out.insert(out.end(), data, data + length);
      continue;
    }
    const std::size_t count = (*a)["count"];
    const std::size_t element = component_size((*a)["componentType"]) * components((*a)["type"]);
    const std::size_t stride = view.value("byteStride", element);
    Bytes encoded;
    std::string mode;
    if (index_views.count(v)) {
      mode = "TRIANGLES";
      if (element == 4) {
        std::vector<std::uint32_t> idx(count);
        std::memcpy(idx.data(), data, 4 * count);
        encoded.resize(meshopt_encodeIndexBufferBound(count, 1u << 24));
        encoded.resize(
            meshopt_encodeIndexBuffer(encoded.data(), encoded.size(), idx.data(), count));
      } else {
        std::vector<std::uint16_t> idx(count);
        std::memcpy(idx.data(), data, 2 * count);
        encoded.resize(meshopt_encodeIndexBufferBound(count, 65536));
        encoded.resize(
            meshopt_encodeIndexBuffer(encoded.data(), encoded.size(), idx.data(), count));
      }
    } else {
      mode = "ATTRIBUTES";
      if (stride % 4 || stride > 256) throw std::runtime_error("stride not a multiple of 4");
      encoded.resize(meshopt_encodeVertexBufferBound(count, stride));
      encoded.resize(
          meshopt_encodeVertexBuffer(encoded.data(), encoded.size(), data, count, stride));
    }
    if (encoded.empty()) throw std::runtime_error("meshopt encoding failed");
    view["buffer"] = 1; // the fallback: same offsets as before
    view["extensions"]["EXT_meshopt_compression"] = {
        {"buffer", 0},          {"byteOffset", out.size()}, {"byteLength", encoded.size()},
        {"byteStride", stride}, {"count", count},           {"mode", mode}};
    out.insert(out.end(), encoded.begin(), encoded.end());
    raw += length;
    packed += encoded.size();
  }
  align4(out);
  doc["buffers"] =
      json::array({{{"byteLength", out.size()}},
                   {{"byteLength", bin_length},
                    {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}});
  for (const char* list : {"extensionsUsed", "extensionsRequired"}) {
    if (!doc.contains(list)) doc[list] = json::array();
    doc[list].push_back("EXT_meshopt_compression");
  }
  Bytes text;
  const std::string dumped = doc.dump();
  text.assign(dumped.begin(), dumped.end());
  align4(text, ' ');
  Bytes glb{'g', 'l', 'T', 'F'};
  put32(glb, 2);
  put32(glb, std::uint32_t(12 + 8 + text.size() + 8 + out.size()));
  put32(glb, std::uint32_t(text.size()));
  glb.insert(glb.end(), {'J', 'S', 'O', 'N'});
  glb.insert(glb.end(), text.begin(), text.end());
  put32(glb, std::uint32_t(out.size()));
  glb.insert(glb.end(), {'B', 'I', 'N', 0});
  glb.insert(glb.end(), out.begin(), out.end());
  std::ofstream o(argv[2], std::ios::binary | std::ios::trunc);
  o.write(reinterpret_cast<const char*>(glb.data()), std::streamsize(glb.size()));
  if (!o) throw std::runtime_error(std::string("cannot write ") + argv[2]);
  std::printf("%s: %zu bytes of accessor views compressed to %zu (%.1f%%), file %zu bytes\n",
              argv[2], raw, packed, 100.0 * double(packed) / double(raw), glb.size());
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "meshopt_glb: %s\n", e.what());
  return 1;
}
