// The camera's cluster hierarchy (core/mesh/hierarchy/mesh_clusters.h, ClusterOptions::camera) and
// the G-buffer drawn through it (raster/passes/camera_lod.h): one material per tree, every opaque
// triangle once, seams of normals kept; on a finely tessellated height field seen at a grazing
// angle, no pixel loses its surface or turns its normal away from the camera, the cut draws a
// fraction of the triangles, and the rendered image stays close to the one drawn from every
// triangle.
#include "core/camera/view.h"
#include "core/image/image_metrics.h"
#include "core/mesh/hierarchy/cluster_cache.h"
#include "core/mesh/hierarchy/mesh_clusters.h"
#include "core/mesh/sphere_mesh.h"
#include "core/scene/scene_builder.h"
#include "raster/context/gl_context.h"
#include "raster/passes/camera_lod.h"
#include "raster/passes/camera_passes.h"
#include "raster/raster_renderer.h"
#include "raster/scene/gpu_scene.h"
#include "tests/height_field.h"
#include "walk/rays/ray_scene.h"
#include "walk/vpls/quasi_random_walk.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <map>

namespace irad {
namespace IRAD_UNITY_ID {

using namespace test_support;

// A cube of flat faces (24 vertices: its corners repeated per face with that face's normal).
void add_cube(Scene& s, const glm::vec3& lo, const glm::vec3& hi, std::uint32_t material) {
  const glm::vec3 p[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z},
                          {lo.x, hi.y, lo.z}, {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z},
                          {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
  const int faces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                           {3, 7, 6, 2}, {0, 4, 7, 3}, {1, 2, 6, 5}};
  for (const auto& f : faces) add_quad(s, p[f[0]], p[f[1]], p[f[2]], p[f[3]], material);
}

TEST(CameraLod, OneMaterialPerTreeEveryOpaqueTriangleOnceSeamsKept) {
  Scene s;
  const std::uint32_t ground = add_material(s, glm::vec3(0.5f));
  const std::uint32_t ball = add_material(s, glm::vec3(0.7f));
  const std::uint32_t box = add_material(s, glm::vec3(0.3f));
  const std::uint32_t leaves = add_material(s, glm::vec3(0.2f));
  s.materials[leaves].alpha_mode = AlphaMode::Mask;
  add_terrain(s, 40, ground);
  add_sphere(s, {0.0f, 0.5f, 0.0f}, 0.2f, 30, ball);
  add_cube(s, glm::vec3(0.4f), glm::vec3(0.6f), box);
  add_quad(s, {-1, 1, -1}, {-1, 1, 1}, {1, 1, 1}, {1, 1, -1}, leaves);
  finish(s);
  ClusterOptions options = camera_cluster_options();
  options.leaf_triangles = 128;
  const MeshClusters c = build_mesh_clusters(s, options);
  ASSERT_EQ(validate_clusters(c, s.positions.size(), s.triangle_count(), s.materials.size()), "");
  ASSERT_EQ(c.root_materials.size(), c.roots.size());
  EXPECT_TRUE(c.levels.empty()); // no coarser levels: their borders move
  // Every opaque triangle (its vertices as the weld leaves them) in exactly one leaf, under a
  // root of its material.
  std::map<std::array<glm::vec3, 3>, std::uint32_t,
           bool (*)(const std::array<glm::vec3, 3>&, const std::array<glm::vec3, 3>&)>
      material_at([](const std::array<glm::vec3, 3>& a, const std::array<glm::vec3, 3>& b) {
        for (int k = 0; k < 3; ++k)
          for (int i = 0; i < 3; ++i)
            if (a[k][i] != b[k][i]) return a[k][i] < b[k][i];
        return false;
      });
  std::size_t opaque = 0;
  for (std::size_t t = 0; t < s.triangle_count(); ++t) {
    if (s.material_of(t).alpha_mode != AlphaMode::Opaque) continue;
    ++opaque;
    const glm::uvec3 v = s.triangles[t];
    material_at[{s.positions[v.x], s.positions[v.y], s.positions[v.z]}] = s.triangle_material[t];
  }
  std::size_t leaf_triangles = 0;
  for (std::size_t r = 0; r < c.roots.size(); ++r) {
    const ClusterNode& root = c.nodes[static_cast<std::size_t>(c.roots[r])];
    for (std::uint32_t k = root.leaf_first; k < root.leaf_first + root.leaf_count; k += 3) {
      const std::uint32_t a = c.indices[k], b = c.indices[k + 1], d = c.indices[k + 2];
      const auto found = material_at.find({s.positions[a], s.positions[b], s.positions[d]});
      ASSERT_NE(found, material_at.end()) << "a leaf triangle that is no opaque triangle";
      EXPECT_EQ(found->second, c.root_materials[r]);
      ++leaf_triangles;
      // Each index draws the attributes the triangle had: the cube's faces keep their own flat
      // normals at the corners they share (a weld of positions alone would mix them).
      if (c.root_materials[r] == box) {
        const glm::vec3 flat = glm::normalize(
            glm::cross(s.positions[b] - s.positions[a], s.positions[d] - s.positions[a]));
        for (std::uint32_t i : {a, b, d}) EXPECT_GT(glm::dot(s.normals[i], flat), 0.9999f);
      }
    }
  }
  EXPECT_EQ(leaf_triangles, opaque);
  EXPECT_EQ(c.original_indices, 3 * opaque);
}

TEST(CameraLod, KeyedByEveryAttributeApartFromTheShadowHierarchy) {
  Scene s = lit_terrain(16);
  const ClusterOptions shadow{}, camera = camera_cluster_options();
  const ClusterKey shadow_key = cluster_key(s, shadow), camera_key = cluster_key(s, camera);
  EXPECT_NE(shadow_key, camera_key);
  s.normals[7] = glm::normalize(s.normals[7] + glm::vec3(0.1f, 0.0f, 0.0f));
  EXPECT_EQ(cluster_key(s, shadow), shadow_key); // the shadows read positions alone
  EXPECT_NE(cluster_key(s, camera), camera_key);
  const ClusterKey normal_changed = cluster_key(s, camera);
  s.triangle_material[3] = 1;
  EXPECT_NE(cluster_key(s, camera), normal_changed);
}

// A terrain of 2 x 300^2 triangles seen at a grazing angle (its far bumps' silhouettes, where a
// simplified triangle can tip over), at 96 x 72: every pixel that sees the surface with every
// triangle sees it through the hierarchy, with a normal toward the camera and a position within
// the error the cut allows; the cut draws fewer triangles.
TEST(CameraLod, NoPixelLosesItsSurfaceOrTurnsAway) {
  const Scene s = lit_terrain(300);
  const View view = make_view(s.cameras[0], s.bounds, 96, 72);
  const auto context = gl::create_osmesa_context();
  const gl::CurrentScope current(*context);
  const GladGLContext& api = context->api();
  const gl::GpuScene gpu(api, s);
  gl::CameraLod lod(api, gpu, build_mesh_clusters(s, camera_cluster_options()));
  lod.prepare(view);
  const GBufferPixels full = draw_gbuffer(api, gpu, view, nullptr);
  const GBufferPixels cut = draw_gbuffer(api, gpu, view, &lod);
  const gl::PixelError allowed = gl::pixel_error(view, gl::CameraLod::kPixels);
  // Whether every neighbour of pixel i sees the surface (with every triangle): a silhouette
  // against the background moves by up to the error, a pixel inside it must keep its surface.
  const int w = view.width, h = view.height;
  const auto inside = [&](std::size_t i) {
    const int x = static_cast<int>(i) % w, y = static_cast<int>(i) / w;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int u = x + dx, v = y + dy;
        if (u < 0 || v < 0 || u >= w || v >= h || full.position[std::size_t(v * w + u)].w == 0.0f)
          return false;
      }
    return true;
  };
  std::size_t surface = 0, lost = 0, turned = 0, beyond = 0;
  for (std::size_t i = 0; i < full.position.size(); ++i) {
    if (full.position[i].w == 0.0f) continue;
    ++surface;
    if (cut.position[i].w == 0.0f) {
      if (inside(i)) ++lost;
      continue;
    }
    const glm::vec3 p(cut.position[i]), to_eye = view.eye - p;
    if (glm::dot(glm::vec3(cut.normal[i]), to_eye) < 0.0f &&
        glm::dot(glm::vec3(full.normal[i]), view.eye - glm::vec3(full.position[i])) > 0.0f)
      ++turned;
    // Along the pixel's ray the two surfaces may lie apart by far more than the error where the
    // ray grazes them; across it, by the error: the distance to the eye differs by at most the
    // error over the cosine, so count the pixels whose depths differ by over 10 times the error.
    const float d = glm::length(to_eye);
    const float depth_gap = std::abs(d - glm::length(view.eye - glm::vec3(full.position[i])));
    if (depth_gap > 10.0f * allowed.per_distance * d) ++beyond;
  }
  std::printf("%zu surface pixels: %zu lost, %zu turned away, %zu beyond 10x the error; "
              "%zu of %zu triangles drawn\n",
              surface, lost, turned, beyond, lod.triangles(), s.triangle_count());
  EXPECT_GT(surface, full.position.size() / 2);
  EXPECT_EQ(lost, 0u);
  EXPECT_LE(turned, surface / 1000); // smooth normals at grazing angles (measured: 0)
  EXPECT_LT(beyond, surface / 100);  // silhouette pixels: a different bump in front (measured: 0)
  // The frustum and the meshes within kPixels: 139,618 of 180,002 drawn (measured). The
  // simplifier's first halving already leaves edges of 5.5 quads (the longest, which bounds a
  // node), so the cut coarsens slowly.
  EXPECT_LT(lod.triangles(), s.triangle_count() * 9 / 10);
}

// The whole render, the hierarchy's G-buffer against every triangle's, over the same VPLs.
TEST(CameraLod, TheImageStaysCloseToEveryTriangles) {
  Log log([](const std::string&) {});
  const Scene s = lit_terrain(300);
  const View view = make_view(s.cameras[0], s.bounds, 96, 72);
  const RayScene rays(s);
  const VplSet vpls = quasi_random_walk(s, rays, {256}, log);
  Image images[2];
  for (int k = 0; k < 2; ++k) {
    RasterOptions o;
    o.camera_lod = k == 0 ? CameraLodMode::Off : CameraLodMode::On;
    o.hierarchy_cache.clear();
    RasterTimings timings;
    images[k] = RasterRenderer(s, o).render(view, vpls, &timings);
    EXPECT_EQ(timings.camera_triangles > 0, k == 1);
    EXPECT_EQ(timings.gpu_camera_pages_bytes > 0, k == 1);
    EXPECT_GT(timings.gpu_shadow_pages_bytes, 0u);
    EXPECT_GT(timings.gpu_scene_bytes, 0u);
  }
  const double error = compare_images(images[1], images[0]).relmse;
  std::printf("relMSE of the hierarchy's image against every triangle's: %.3g\n", error);
  EXPECT_LT(error, 1e-4); // measured: 2.96e-5
}

} // namespace IRAD_UNITY_ID
} // namespace irad
