// EXT_meshopt_compression through Debian's libmeshoptimizer (0.18). The library asserts on
// strides and counts it does not support (and the asserts are compiled out of the release
// library), so every such rule is checked here first.
#include "core/gltf/decode/codecs.h"

#include <limits>

#include <fmt/format.h>
#include <meshoptimizer.h>

namespace irad::gltf {

namespace {

enum class Mode { Attributes, Triangles, Indices };
enum class Filter { None, Octahedral, Quaternion, Exponential };

Mode parse_mode(std::string_view mode) {
  if (mode == "ATTRIBUTES") return Mode::Attributes;
  if (mode == "TRIANGLES") return Mode::Triangles;
  if (mode == "INDICES") return Mode::Indices;
  throw CodecError(fmt::format("unknown meshopt mode \"{}\"", mode));
}

Filter parse_filter(std::string_view filter) {
  if (filter == "NONE") return Filter::None;
  if (filter == "OCTAHEDRAL") return Filter::Octahedral;
  if (filter == "QUATERNION") return Filter::Quaternion;
  if (filter == "EXPONENTIAL") return Filter::Exponential;
  throw CodecError(fmt::format("unknown meshopt filter \"{}\"", filter));
}

// The EXT_meshopt_compression rules on byteStride, count and filter for each mode.
void check_layout(Mode mode, Filter filter, std::size_t count, std::size_t stride) {
  if (mode == Mode::Attributes) {
    if (stride == 0 || stride > 256 || stride % 4 != 0) {
      throw CodecError(fmt::format(
          "meshopt ATTRIBUTES: byteStride {} is not a multiple of 4 in 4..256", stride));
    }
  } else {
    if (stride != 2 && stride != 4) {
      throw CodecError(fmt::format("meshopt {}: byteStride {} is neither 2 nor 4",
                                   mode == Mode::Triangles ? "TRIANGLES" : "INDICES", stride));
    }
    if (filter != Filter::None) {
      throw CodecError("meshopt: a filter other than NONE outside ATTRIBUTES mode");
    }
    if (mode == Mode::Triangles && count % 3 != 0) {
      throw CodecError(fmt::format("meshopt TRIANGLES: count {} is not a multiple of 3", count));
    }
  }
  if (filter == Filter::Octahedral && stride != 4 && stride != 8) {
    throw CodecError(fmt::format("meshopt OCTAHEDRAL: byteStride {} is neither 4 nor 8", stride));
  }
  if (filter == Filter::Quaternion && stride != 8) {
    throw CodecError(fmt::format("meshopt QUATERNION: byteStride {} is not 8", stride));
  }
  // EXPONENTIAL: any multiple of 4, which ATTRIBUTES already requires.
}

void apply_filter(Filter filter, std::vector<unsigned char>& out, std::size_t count,
                  std::size_t stride) {
  switch (filter) {
  case Filter::None:
    break;
  case Filter::Octahedral:
    meshopt_decodeFilterOct(out.data(), count, stride);
    break;
  case Filter::Quaternion:
    meshopt_decodeFilterQuat(out.data(), count, stride);
    break;
  case Filter::Exponential:
    meshopt_decodeFilterExp(out.data(), count, stride);
    break;
  }
}

} // namespace

std::vector<unsigned char> decode_meshopt(const unsigned char* data, std::size_t size,
                                          std::size_t count, std::size_t byte_stride,
                                          std::string_view mode, std::string_view filter) {
  const Mode m = parse_mode(mode);
  const Filter f = parse_filter(filter);
  check_layout(m, f, count, byte_stride);
  if (count > std::numeric_limits<std::size_t>::max() / byte_stride) {
    throw CodecError(fmt::format("meshopt: {} elements of {} bytes overflow", count, byte_stride));
  }
  std::vector<unsigned char> out(count * byte_stride);
  if (count == 0) return out;
  if (!data) throw CodecError("meshopt: no compressed data");
  int status = 0;
  switch (m) {
  case Mode::Attributes:
    status = meshopt_decodeVertexBuffer(out.data(), count, byte_stride, data, size);
    break;
  case Mode::Triangles:
    status = meshopt_decodeIndexBuffer(out.data(), count, byte_stride, data, size);
    break;
  case Mode::Indices:
    status = meshopt_decodeIndexSequence(out.data(), count, byte_stride, data, size);
    break;
  }
  if (status != 0) {
    throw CodecError(fmt::format("the meshopt {} data do not decode (corrupt or truncated)", mode));
  }
  apply_filter(f, out, count, byte_stride);
  return out;
}

} // namespace irad::gltf
