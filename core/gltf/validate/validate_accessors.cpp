// Accessors on their own: layout inside their buffer view, sparse storage, and their data
// against the declared min/max.
#include "core/gltf/validate/validate_semantics_read.h"

#include <cmath>

namespace irad::gltf::sem {

using nlohmann::json;

namespace {

bool is_matrix(const AccessorView& a) {
  return a.type.size() == 4 && a.type.rfind("MAT", 0) == 0;
}

void check_layout(const Context& ctx, const AccessorView& a, const std::string& ptr) {
  const json* bv = ctx.object("bufferViews", *a.buffer_view);
  if (bv == nullptr) return;
  if (a.byte_offset % a.comp_size != 0)
    ctx.add(at(ptr, "byteOffset"), "ACCESSOR_OFFSET_ALIGNMENT",
            "byteOffset is not a multiple of the component size");
  if (is_matrix(a) && a.comp_size < 4 && a.byte_offset % 4 != 0)
    ctx.add(at(ptr, "byteOffset"), "ACCESSOR_MATRIX_ALIGNMENT",
            "a matrix accessor must start on a 4-byte boundary");
  const std::int64_t view_offset = index(*bv, "byteOffset").value_or(0);
  if (sane(view_offset) && (view_offset + a.byte_offset) % a.comp_size != 0)
    ctx.add(ptr, "ACCESSOR_TOTAL_OFFSET_ALIGNMENT",
            "the view's and the accessor's byteOffset together are not a multiple of the "
            "component size");
  if (a.byte_stride && *a.byte_stride < element_size(a))
    ctx.add(ptr, "ACCESSOR_SMALL_BYTESTRIDE", "the view's byteStride is smaller than one element");
  const auto view_length = index(*bv, "byteLength");
  if (!view_length || a.count == 0 || !sane(*view_length)) return;
  const std::int64_t stride = a.byte_stride.value_or(element_size(a));
  const std::int64_t length = stride * (a.count - 1) + last_element_size(a);
  if (a.byte_offset >= *view_length)
    ctx.add(at(ptr, "byteOffset"), "ACCESSOR_TOO_LONG", "the accessor starts past its view's end");
  else if (a.byte_offset + length > *view_length)
    ctx.add(ptr, "ACCESSOR_TOO_LONG", "the accessor's data does not fit its buffer view");
}

// Sparse indices: fewer than the base accessor's elements, strictly increasing, in range.
void check_sparse(const Context& ctx, const json& acc, const AccessorView& a,
                  const std::string& ptr) {
  const json* sparse = member(acc, "sparse");
  const auto count = sparse ? index(*sparse, "count") : std::nullopt;
  if (!count) return;
  const std::string sp = at(ptr, "sparse");
  if (*count > a.count) {
    ctx.add(at(sp, "count"), "ACCESSOR_SPARSE_COUNT_OUT_OF_RANGE",
            "the sparse count is greater than the accessor's count");
    return;
  }
  const json* indices = member(*sparse, "indices");
  if (indices == nullptr || !indices->is_object()) return;
  std::vector<double> values;
  if (*count > 0x1000000 ||
      !read_packed(ctx, *indices, *count, index(*indices, "componentType").value_or(0), 1, values))
    return;
  for (std::size_t k = 0; k < values.size(); ++k) {
    if (values[k] >= static_cast<double>(a.count)) {
      ctx.add(at(sp, "indices"), "ACCESSOR_SPARSE_INDEX_OOB",
              "a sparse index is not less than the accessor's count");
      return;
    }
    if (k > 0 && values[k] <= values[k - 1]) {
      ctx.add(at(sp, "indices"), "ACCESSOR_SPARSE_INDICES_NON_INCREASING",
              "the sparse indices are not strictly increasing");
      return;
    }
  }
}

std::string format(double v) {
  std::string s = std::to_string(v);
  while (s.size() > 1 && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  return s;
}

// Declared bounds against the data, component by component.
void check_bounds(const Context& ctx, const json& acc, const AccessorView& a, const AccessorData& d,
                  const std::string& ptr) {
  const bool is_float = a.component_type == kFloat;
  const auto n = static_cast<std::size_t>(a.components);
  for (const char* key : {"min", "max"}) {
    const auto declared = numbers(acc, key);
    if (!declared || declared->size() != n || a.count == 0) continue;
    const bool is_min = key[1] == 'i';
    for (std::size_t c = 0; c < n; ++c) {
      double actual = is_min ? HUGE_VAL : -HUGE_VAL;
      std::size_t outside = 0;
      const double want =
          is_float ? static_cast<double>(static_cast<float>((*declared)[c])) : (*declared)[c];
      for (std::size_t e = c; e < d.values.size(); e += n) {
        const double v = d.values[e];
        if (!std::isfinite(v)) continue;
        actual = is_min ? std::min(actual, v) : std::max(actual, v);
        if (is_min ? v < want : v > want) ++outside;
      }
      if (!std::isfinite(actual)) continue;
      const std::string cp = at(at(ptr, key), static_cast<std::int64_t>(c));
      if (actual != want)
        ctx.add(cp, is_min ? "ACCESSOR_MIN_MISMATCH" : "ACCESSOR_MAX_MISMATCH",
                std::string("declared ") + key + " " + format(want) + " but the data's is " +
                    format(actual));
      if (outside > 0)
        ctx.add(cp,
                is_min ? "ACCESSOR_ELEMENT_OUT_OF_MIN_BOUND" : "ACCESSOR_ELEMENT_OUT_OF_MAX_BOUND",
                std::to_string(outside) + " element(s) lie outside the declared " + key);
    }
  }
}

void check_accessor(const Context& ctx, const json& acc, std::int64_t i) {
  const auto a = accessor_view(ctx, i);
  if (!a || !a->valid) return;
  const std::string ptr = at("/accessors", i);
  if (a->normalized && (a->component_type == kFloat || a->component_type == kUnsignedInt))
    ctx.add(at(ptr, "normalized"), "ACCESSOR_NORMALIZED_INVALID",
            "only byte and short accessors can be normalized");
  if (a->buffer_view) check_layout(ctx, *a, ptr);
  check_sparse(ctx, acc, *a, ptr);
  const AccessorData d = read_accessor(ctx, i);
  if (!d.ok) return;
  if (a->component_type == kFloat) {
    for (std::size_t e = 0; e < d.values.size(); ++e) {
      if (std::isfinite(d.values[e])) continue;
      ctx.add(ptr, "ACCESSOR_INVALID_FLOAT",
              "component " + std::to_string(e) + " is NaN or infinite");
      break;
    }
  }
  check_bounds(ctx, acc, *a, d, ptr);
}

} // namespace

void check_accessors(const Context& ctx) {
  const json& accessors = ctx.list("accessors");
  for (std::size_t i = 0; i < accessors.size(); ++i)
    if (accessors[i].is_object()) check_accessor(ctx, accessors[i], static_cast<std::int64_t>(i));
}

} // namespace irad::gltf::sem
