// Animations: sampler accessors (formats, bounds, timing data), channels against their target
// nodes, and the output accessors' counts and quaternions.
#include "core/gltf/validate/validate_semantics_read.h"

#include <cmath>
#include <map>

namespace irad::gltf::sem {

using nlohmann::json;

namespace {

void check_input(const Context& ctx, std::int64_t acc, bool cubic, const std::string& ptr) {
  const auto a = accessor_view(ctx, acc);
  if (!a || !a->valid) return;
  if (a->byte_stride)
    ctx.add(ptr, "ANIMATION_SAMPLER_ACCESSOR_WITH_BYTESTRIDE",
            "an animation accessor's buffer view cannot have a byteStride");
  if (a->type != "SCALAR" || a->component_type != kFloat) {
    ctx.add(ptr, "ANIMATION_SAMPLER_INPUT_ACCESSOR_INVALID_FORMAT",
            "input times must be SCALAR FLOAT");
    return;
  }
  const json& obj = *ctx.object("accessors", acc);
  if (!has(obj, "min") || !has(obj, "max"))
    ctx.add(ptr, "ANIMATION_SAMPLER_INPUT_ACCESSOR_WITHOUT_BOUNDS",
            "the input accessor must declare min and max");
  if (cubic && a->count < 2)
    ctx.add(ptr, "ANIMATION_SAMPLER_INPUT_ACCESSOR_TOO_FEW_ELEMENTS",
            "a CUBICSPLINE sampler needs at least 2 keyframes");
  const AccessorData d = read_accessor(ctx, acc);
  if (!d.ok) return;
  bool negative = false, non_increasing = false;
  for (std::size_t k = 0; k < d.values.size(); ++k) {
    if (d.values[k] < 0) negative = true;
    if (k > 0 && !(d.values[k] > d.values[k - 1])) non_increasing = true;
  }
  if (negative) ctx.add(ptr, "ACCESSOR_ANIMATION_INPUT_NEGATIVE", "an input time is negative");
  if (non_increasing)
    ctx.add(ptr, "ACCESSOR_ANIMATION_INPUT_NON_INCREASING", "input times are not increasing");
}

bool normalized_int(const AccessorView& a) {
  return a.normalized && a.component_type != kFloat && a.component_type != kUnsignedInt;
}

bool output_format_ok(const std::string& path, const AccessorView& a, bool quantized) {
  if (path == "translation" || path == "scale")
    return a.type == "VEC3" && (a.component_type == kFloat || (quantized && a.comp_size < 4));
  if (path == "rotation")
    return a.type == "VEC4" && (a.component_type == kFloat || normalized_int(a));
  if (path == "weights")
    return a.type == "SCALAR" && (a.component_type == kFloat || normalized_int(a));
  return true;
}

void check_quaternions(const Context& ctx, std::int64_t acc, bool cubic, const std::string& ptr) {
  const auto a = accessor_view(ctx, acc);
  const AccessorData d = read_accessor(ctx, acc);
  if (!a || !d.ok || a->components != 4) return;
  const double tol = a->component_type == kFloat ? 0.0005 : (a->comp_size == 1 ? 0.02 : 0.001);
  const std::size_t elements = d.values.size() / 4;
  for (std::size_t e = cubic ? 1 : 0; e < elements; e += cubic ? 3 : 1) {
    double len2 = 0;
    for (std::size_t c = 0; c < 4; ++c) {
      const double v = normalize(d.values[e * 4 + c], a->component_type, a->normalized);
      len2 += v * v;
    }
    if (!std::isfinite(len2) || std::fabs(std::sqrt(len2) - 1.0) <= tol) continue;
    ctx.add(ptr, "ACCESSOR_ANIMATION_SAMPLER_OUTPUT_NON_NORMALIZED_QUATERNION",
            "a rotation keyframe is not a unit quaternion");
    return;
  }
}

struct Channel {
  const json& sampler;
  const json& node;
  std::string path;
  std::string ptr; // /animations/a/channels/c
};

// The channel's sampler output against its target: format, count, quaternion lengths.
void check_output(const Context& ctx, const Channel& ch) {
  const auto in = index(ch.sampler, "input");
  const auto out = index(ch.sampler, "output");
  const auto ia = in ? accessor_view(ctx, *in) : std::nullopt;
  const auto oa = out ? accessor_view(ctx, *out) : std::nullopt;
  if (!oa || !oa->valid) return;
  const std::string sp = at(ch.ptr, "sampler");
  if (!output_format_ok(ch.path, *oa, extension_used(ctx.root, "KHR_mesh_quantization"))) {
    ctx.add(sp, "ANIMATION_SAMPLER_OUTPUT_ACCESSOR_INVALID_FORMAT",
            "the output accessor's format does not suit path '" + ch.path + "'");
    return;
  }
  const bool cubic = string(ch.sampler, "interpolation") == "CUBICSPLINE";
  std::optional<std::int64_t> per_key = 1;
  if (ch.path == "weights") {
    const auto m = index(ch.node, "mesh");
    const json* mesh = m ? ctx.object("meshes", *m) : nullptr;
    const json* p0 = mesh != nullptr ? element(*mesh, "primitives", 0) : nullptr;
    per_key =
        p0 != nullptr
            ? std::optional<std::int64_t>(static_cast<std::int64_t>(array_size(*p0, "targets")))
            : std::nullopt;
  }
  if (ia && ia->valid && per_key && *per_key > 0 && *per_key < (std::int64_t{1} << 16) &&
      oa->count != ia->count * *per_key * (cubic ? 3 : 1))
    ctx.add(sp, "ANIMATION_SAMPLER_OUTPUT_ACCESSOR_INVALID_COUNT",
            "the output accessor's count does not match the input's keyframes");
  if (ch.path == "rotation") check_quaternions(ctx, *out, cubic, sp);
}

void check_channel(const Context& ctx, const Channel& ch) {
  const std::string tp = at(ch.ptr, "target");
  const bool trs = ch.path == "translation" || ch.path == "rotation" || ch.path == "scale";
  if (trs && has(ch.node, "matrix"))
    ctx.add(tp, "ANIMATION_CHANNEL_TARGET_NODE_MATRIX",
            "a channel cannot animate the TRS of a node that has a matrix");
  if (ch.path == "weights") {
    const auto m = index(ch.node, "mesh");
    const json* mesh = m ? ctx.object("meshes", *m) : nullptr;
    const json* p0 = mesh != nullptr ? element(*mesh, "primitives", 0) : nullptr;
    if (mesh == nullptr || (p0 != nullptr && array_size(*p0, "targets") == 0))
      ctx.add(tp, "ANIMATION_CHANNEL_TARGET_NODE_WEIGHTS_NO_MORPHS",
              "a channel animates weights of a node without morph targets");
  }
  check_output(ctx, ch);
}

void check_animation(const Context& ctx, const json& anim, std::int64_t a) {
  const std::string ap = at("/animations", a);
  const json* samplers = member(anim, "samplers");
  if (samplers != nullptr && samplers->is_array()) {
    for (std::size_t s = 0; s < samplers->size(); ++s) {
      const json& sampler = (*samplers)[s];
      const std::string sp = at(at(ap, "samplers"), static_cast<std::int64_t>(s));
      const bool cubic = string(sampler, "interpolation") == "CUBICSPLINE";
      if (const auto in = index(sampler, "input"); in && ctx.object("accessors", *in))
        check_input(ctx, *in, cubic, at(sp, "input"));
      const auto out = index(sampler, "output");
      const auto oa = out ? accessor_view(ctx, *out) : std::nullopt;
      if (oa && oa->byte_stride)
        ctx.add(at(sp, "output"), "ANIMATION_SAMPLER_ACCESSOR_WITH_BYTESTRIDE",
                "an animation accessor's buffer view cannot have a byteStride");
    }
  }
  const json* channels = member(anim, "channels");
  if (channels == nullptr || !channels->is_array()) return;
  std::map<std::pair<std::int64_t, std::string>, std::size_t> first;
  for (std::size_t c = 0; c < channels->size(); ++c) {
    const json& channel = (*channels)[c];
    const json* target = member(channel, "target");
    if (target == nullptr) continue;
    const auto n = index(*target, "node");
    const auto path = string(*target, "path");
    const json* node = n ? ctx.object("nodes", *n) : nullptr;
    const auto si = index(channel, "sampler");
    const json* sampler = si ? element(anim, "samplers", *si) : nullptr;
    const std::string cp = at(at(ap, "channels"), static_cast<std::int64_t>(c));
    if (node == nullptr || !path) continue;
    const auto [it, inserted] = first.emplace(std::make_pair(*n, *path), c);
    if (!inserted)
      ctx.add(at(at(at(ap, "channels"), static_cast<std::int64_t>(it->second)), "target"),
              "ANIMATION_DUPLICATE_TARGETS",
              "channels " + std::to_string(it->second) + " and " + std::to_string(c) +
                  " animate the same property");
    static const json no_sampler = json::object(); // immutable
    const bool ok = sampler != nullptr && sampler->is_object();
    check_channel(ctx, Channel{ok ? *sampler : no_sampler, *node, *path, cp});
  }
}

} // namespace

void check_animations(const Context& ctx) {
  const json& anims = ctx.list("animations");
  for (std::size_t a = 0; a < anims.size(); ++a)
    if (anims[a].is_object()) check_animation(ctx, anims[a], static_cast<std::int64_t>(a));
}

} // namespace irad::gltf::sem
