#pragma once
// What the shadow hierarchy's tests share: the Cornell box with a tessellated sphere, its VPLs
// and a view; the indices the GPU holds for a selection of the hierarchy's pages.
#include "core/camera/view.h"
#include "core/gltf/loader.h"
#include "core/mesh/sphere_mesh.h"
#include "core/scene/scene_builder.h"
#include "raster/shadow/shadow_lod.h"
#include "tests/test_paths.h"
#include "walk/vpls/quasi_random_walk.h"

#include <algorithm>
#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace irad::test_support {

struct SphereBox {
  Scene s;
  VplSet vpls;
  View view;
};

// The Cornell box with a sphere of 2 rings^2 triangles floating in it (which the faces draw
// simplified), 16 x 64 paths' VPLs and a 64x64 view.
inline SphereBox sphere_box(int rings) {
  Log log([](const std::string&) {});
  SphereBox b;
  b.s = load_gltf(std::filesystem::path(IRAD_SOURCE_DIR) / "data/cornell_box.gltf", log);
  add_sphere(b.s, {0.3f, 0.33f, 0.3f}, 0.09f, rings, add_material(b.s, glm::vec3(0.7f)));
  finish(b.s);
  b.vpls = quasi_random_walk(b.s, RayScene(b.s), {16, 64}, log);
  b.view = make_view(b.s.cameras.at(0), b.s.bounds, 64, 64);
  return b;
}

// The indices `selection`'s ranges draw, read back from its slabs, slab by slab, range by range.
inline std::vector<std::uint32_t> selected_indices(const GladGLContext& api,
                                                   const gl::ClusterSelection& selection) {
  std::vector<std::uint32_t> out;
  for (const gl::ClusterSelection::Slab& slab : selection.slabs) {
    GLint size = 0;
    api.BindBuffer(GL_COPY_READ_BUFFER, slab.buffer);
    api.GetBufferParameteriv(GL_COPY_READ_BUFFER, GL_BUFFER_SIZE, &size);
    std::vector<std::uint32_t> words(static_cast<std::size_t>(size) / 4);
    api.GetBufferSubData(GL_COPY_READ_BUFFER, 0, size, words.data());
    for (std::size_t r = 0; r < slab.counts.size(); ++r) {
      const auto at =
          static_cast<std::ptrdiff_t>(reinterpret_cast<std::uintptr_t>(slab.offsets[r]) / 4);
      out.insert(out.end(), words.begin() + at, words.begin() + at + slab.counts[r]);
    }
  }
  api.BindBuffer(GL_COPY_READ_BUFFER, 0);
  return out;
}

// The triangles of an index list, sorted (what a draw covers, whatever its order).
inline std::vector<std::array<std::uint32_t, 3>> triangle_set(const std::vector<std::uint32_t>& v) {
  std::vector<std::array<std::uint32_t, 3>> t;
  for (std::size_t k = 0; k + 2 < v.size(); k += 3) t.push_back({v[k], v[k + 1], v[k + 2]});
  std::sort(t.begin(), t.end());
  return t;
}

} // namespace irad::test_support
