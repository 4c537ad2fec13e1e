#include "core/gltf/read/triangle_list.h"

#include "core/gltf/read/accessors.h"
#include "core/mesh/hierarchy/stored_indices.h"
#include "core/util/freed_memory.h"
#include "core/util/parallel_rows.h"

#include <atomic>
#include <fmt/format.h>
#include <limits>
#include <numeric>
#include <span>

namespace irad::gltf {

namespace {

// Vertex indices of the primitive (0, 1, ..., n - 1 when it has none).
std::vector<std::uint32_t> read_vertex_indices(const Context& ctx, const json& p, std::size_t n,
                                               const std::string& where) {
  const auto accessor = index_member(p, "indices");
  if (!accessor) {
    if (n > std::numeric_limits<std::uint32_t>::max()) ctx.fail(where, "too many vertices");
    std::vector<std::uint32_t> indices(n);
    std::iota(indices.begin(), indices.end(), std::uint32_t(0));
    return indices;
  }
  return read_indices(ctx, *accessor, where + ".indices");
}

void check_index_range(const Context& ctx, std::span<const std::uint32_t> indices, std::size_t n,
                       const std::string& where) {
  std::atomic<bool> bad{false};
  parallel_chunks(indices.size(), [&](std::size_t first, std::size_t end) {
    if (!below(indices.data() + first, end - first, n)) bad = true;
  });
  if (!bad) return;
  for (std::uint32_t i : indices) { // the first one out of range, for the message
    if (i >= n) {
      ctx.fail(where, fmt::format("index value {} out of range ({} vertices)", i, n));
    }
  }
}

void check_triangle_limit(const Context& ctx, std::uint64_t more, std::size_t before,
                          const std::string& where) {
  const std::uint64_t total = before + more;
  if (total > ctx.limits.max_triangles) {
    ctx.fail(where, "the scene would have " + std::to_string(total) +
                        " triangles, over the limit of " +
                        std::to_string(ctx.limits.max_triangles) + " (--max-triangles)");
  }
}

// Triangle list from the index sequence of a TRIANGLES, TRIANGLE_STRIP or TRIANGLE_FAN primitive
// (strip triangle k: (k, k+1, k+2), odd k (k+1, k, k+2); fan triangle k: (0, k+1, k+2)).
std::vector<glm::uvec3> assemble(const Context& ctx, int mode,
                                 const std::vector<std::uint32_t>& idx, const std::string& where) {
  std::vector<glm::uvec3> out;
  if (mode == kTriangles) {
    if (idx.size() % 3 != 0)
      ctx.warn(where + ": TRIANGLES index count is not a multiple of 3; the "
                       "last incomplete triangle is dropped");
    resize_huge(out, idx.size() / 3);
    parallel_chunks(out.size(), [&](std::size_t first, std::size_t end) {
      for (std::size_t t = first; t < end; ++t)
        out[t] = glm::uvec3(idx[3 * t], idx[3 * t + 1], idx[3 * t + 2]);
    });
  } else if (mode == kTriangleStrip) {
    for (std::size_t k = 0; k + 2 < idx.size(); ++k) {
      if (k % 2 == 0)
        out.emplace_back(idx[k], idx[k + 1], idx[k + 2]);
      else
        out.emplace_back(idx[k + 1], idx[k], idx[k + 2]);
    }
  } else {
    for (std::size_t k = 1; k + 1 < idx.size(); ++k) out.emplace_back(idx[0], idx[k], idx[k + 1]);
  }
  return out;
}

} // namespace

std::uint64_t triangle_count(int mode, std::size_t n) {
  if (mode == kTriangles) return n / 3;
  return n >= 3 ? n - 2 : 0;
}

std::vector<glm::uvec3> read_triangles(const Context& ctx, const json& p, int mode,
                                       std::optional<std::vector<std::uint32_t>> draco,
                                       std::size_t n, std::size_t before,
                                       const std::string& where) {
  const auto accessor = index_member(p, "indices");
  const std::string use = where + ".indices";
  if (!draco && accessor && mode == kTriangles) {
    const std::size_t count = accessor_count(ctx, *accessor, use);
    if (count % 3 == 0) {
      check_triangle_limit(ctx, count / 3, before, where);
      std::vector<glm::uvec3> triangles = read_index_triples(ctx, *accessor, use);
      check_index_range(ctx, {reinterpret_cast<const std::uint32_t*>(triangles.data()), count}, n,
                        use);
      return triangles;
    }
  }
  const std::vector<std::uint32_t> indices =
      draco ? std::move(*draco) : read_vertex_indices(ctx, p, n, where);
  check_index_range(ctx, indices, n, use);
  check_triangle_limit(ctx, triangle_count(mode, indices.size()), before, where);
  return assemble(ctx, mode, indices, where);
}

} // namespace irad::gltf
