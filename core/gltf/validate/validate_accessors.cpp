// Accessors on their own: layout inside their buffer view, sparse storage, and their data
// against the declared min/max.
#include "core/gltf/validate/validate_semantics_read.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>
#include <vector>

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

// Declared bounds against the data, component by component, gathered chunk by chunk.
class BoundsCheck {
public:
  BoundsCheck(const json& acc, const AccessorView& a) : a_(a) {
    const auto n = static_cast<std::size_t>(a.components);
    for (int m = 0; m < 2; ++m) {
      const auto declared = numbers(acc, m == 0 ? "min" : "max");
      if (!declared || declared->size() != n || a.count == 0) continue;
      Side& side = sides_[m];
      side.declared = true;
      for (std::size_t c = 0; c < n; ++c) {
        // A float accessor's bounds as the floats the data is compared with.
        side.want.push_back(a.component_type == kFloat
                                ? static_cast<double>(static_cast<float>((*declared)[c]))
                                : (*declared)[c]);
        side.actual.push_back(m == 0 ? HUGE_VAL : -HUGE_VAL);
      }
      side.outside.assign(n, 0);
    }
  }

  void add(std::span<const double> values) {
    const auto n = static_cast<std::size_t>(a_.components);
    for (int m = 0; m < 2; ++m) {
      Side& side = sides_[m];
      if (!side.declared) continue;
      const bool is_min = m == 0;
      for (std::size_t e = 0; e < values.size(); e += n) {
        for (std::size_t c = 0; c < n; ++c) {
          const double v = values[e + c];
          if (!std::isfinite(v)) continue;
          side.actual[c] = is_min ? std::min(side.actual[c], v) : std::max(side.actual[c], v);
          if (is_min ? v < side.want[c] : v > side.want[c]) ++side.outside[c];
        }
      }
    }
  }

  void report(const Context& ctx, const std::string& ptr) const {
    for (int m = 0; m < 2; ++m) {
      const Side& side = sides_[m];
      const bool is_min = m == 0;
      const char* key = is_min ? "min" : "max";
      for (std::size_t c = 0; side.declared && c < side.want.size(); ++c) {
        if (!std::isfinite(side.actual[c])) continue;
        const std::string cp = at(at(ptr, key), static_cast<std::int64_t>(c));
        if (side.actual[c] != side.want[c])
          ctx.add(cp, is_min ? "ACCESSOR_MIN_MISMATCH" : "ACCESSOR_MAX_MISMATCH",
                  std::string("declared ") + key + " " + format(side.want[c]) +
                      " but the data's is " + format(side.actual[c]));
        if (side.outside[c] > 0)
          ctx.add(cp,
                  is_min ? "ACCESSOR_ELEMENT_OUT_OF_MIN_BOUND"
                         : "ACCESSOR_ELEMENT_OUT_OF_MAX_BOUND",
                  std::to_string(side.outside[c]) + " element(s) lie outside the declared " + key);
      }
    }
  }

private:
  struct Side {
    bool declared = false;
    std::vector<double> want, actual;
    std::vector<std::size_t> outside;
  };
  const AccessorView& a_;
  Side sides_[2]; // min, max
};

void check_accessor(const Context& ctx, const json& acc, std::int64_t i) {
  const auto a = accessor_view(ctx, i);
  if (!a || !a->valid) return;
  const std::string ptr = at("/accessors", i);
  if (a->normalized && (a->component_type == kFloat || a->component_type == kUnsignedInt))
    ctx.add(at(ptr, "normalized"), "ACCESSOR_NORMALIZED_INVALID",
            "only byte and short accessors can be normalized");
  if (a->buffer_view) check_layout(ctx, *a, ptr);
  check_sparse(ctx, acc, *a, ptr);
  BoundsCheck bounds(acc, *a);
  std::optional<std::int64_t> non_finite; // the first NaN or infinite component of a float one
  const auto n = static_cast<std::int64_t>(a->components);
  const bool read =
      stream_accessor(ctx, i, [&](std::span<const double> values, std::int64_t first) {
        for (std::size_t e = 0; !non_finite && a->component_type == kFloat && e < values.size();
             ++e)
          if (!std::isfinite(values[e])) non_finite = first * n + static_cast<std::int64_t>(e);
        bounds.add(values);
      });
  if (!read) return;
  if (non_finite)
    ctx.add(ptr, "ACCESSOR_INVALID_FLOAT",
            "component " + std::to_string(*non_finite) + " is NaN or infinite");
  bounds.report(ctx, ptr);
}

} // namespace

void check_accessors(const Context& ctx) {
  const json& accessors = ctx.list("accessors");
  for (std::size_t i = 0; i < accessors.size(); ++i)
    if (accessors[i].is_object()) check_accessor(ctx, accessors[i], static_cast<std::int64_t>(i));
}

} // namespace irad::gltf::sem
