#pragma once
// Helpers of the edge-antialiasing tests (tests/test_jitter.cpp): a mask of the pixels near
// geometric edges, computed by ray casting (independent of the raster), a box downsample, and
// the error of an image against a reference over a mask.
#include "core/camera/view.h"
#include "core/image/image.h"
#include "core/scene/scene.h"
#include "walk/rays/ray_scene.h"

#include <cmath>
#include <vector>

namespace irad::jitter_test {

// What a ray through image point (x, y) (pixels, y down) sees: the plane (material, normal,
// offset) or nothing.
struct PlaneId {
  bool hit = false;
  std::uint32_t material = 0;
  glm::vec3 normal{0.0f};
  float offset = 0.0f;
};

inline PlaneId plane_at(const Scene& scene, const RayScene& rays, const View& view, float x,
                        float y) {
  const CameraRay ray = image_point_ray(view, x, y);
  const glm::vec3 dir = ray.direction;
  const auto hit = rays.intersect(ray.origin, dir, 0.0f, std::numeric_limits<float>::infinity());
  PlaneId id;
  if (!hit) return id;
  id.hit = true;
  id.material = scene.triangle_material[hit->triangle];
  id.normal = geometric_normal(scene, hit->triangle);
  id.offset = glm::dot(id.normal, ray.origin + hit->t * dir);
  return id;
}

inline bool same_plane(const PlaneId& a, const PlaneId& b, float scale) {
  if (a.hit != b.hit) return false;
  if (!a.hit) return true;
  return a.material == b.material && glm::dot(a.normal, b.normal) > 0.999f &&
         std::abs(a.offset - b.offset) < 1e-3f * scale;
}

// 1 where the pixel's footprint (4 x 4 sub-pixel rays) holds a depth, normal or material
// discontinuity, dilated by `dilate` pixels; 0 elsewhere.
inline std::vector<std::uint8_t> edge_mask(const Scene& scene, const RayScene& rays,
                                           const View& view, int dilate) {
  const int w = view.width, h = view.height;
  const float scale = scene.bounds.diagonal();
  std::vector<std::uint8_t> core(static_cast<std::size_t>(w * h), 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float fx = static_cast<float>(x), fy = static_cast<float>(y);
      const PlaneId centre = plane_at(scene, rays, view, fx + 0.5f, fy + 0.5f);
      for (int s = 0; s < 16 && !core[y * w + x]; ++s) {
        const PlaneId sub =
            plane_at(scene, rays, view, fx + (static_cast<float>(s % 4) + 0.5f) / 4.0f,
                     fy + (static_cast<float>(s / 4) + 0.5f) / 4.0f);
        if (!same_plane(centre, sub, scale)) core[y * w + x] = 1;
      }
    }
  std::vector<std::uint8_t> mask(core.size(), 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int dy = -dilate; dy <= dilate; ++dy)
        for (int dx = -dilate; dx <= dilate; ++dx) {
          const int qx = x + dx, qy = y + dy;
          if (qx >= 0 && qy >= 0 && qx < w && qy < h && core[qy * w + qx]) mask[y * w + x] = 1;
        }
  return mask;
}

// Mean of f x f blocks.
inline Image box_downsample(const Image& image, int f) {
  Image out(image.width() / f, image.height() / f);
  for (int y = 0; y < out.height(); ++y)
    for (int x = 0; x < out.width(); ++x) {
      glm::vec4 sum(0.0f);
      for (int j = 0; j < f; ++j)
        for (int i = 0; i < f; ++i) sum += image.at(f * x + i, f * y + j);
      out.at(x, y) = sum / static_cast<float>(f * f);
    }
  return out;
}

struct MaskedError {
  double rmse = 0.0;   // over R, G, B of the pixels where mask == want
  double relmse = 0.0; // (a - b)^2 / (b^2 + 0.01), the same pixels
  std::size_t pixels = 0;
};

inline MaskedError masked_error(const Image& a, const Image& b,
                                const std::vector<std::uint8_t>& mask, std::uint8_t want) {
  MaskedError e;
  double se = 0.0, rel = 0.0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) {
      if (mask[static_cast<std::size_t>(y * a.width() + x)] != want) continue;
      ++e.pixels;
      for (int c = 0; c < 3; ++c) {
        const double d = a.at(x, y)[c] - b.at(x, y)[c];
        se += d * d;
        rel += d * d / (b.at(x, y)[c] * b.at(x, y)[c] + 1e-2);
      }
    }
  const double n = 3.0 * static_cast<double>(e.pixels);
  e.rmse = std::sqrt(se / n);
  e.relmse = rel / n;
  return e;
}

} // namespace irad::jitter_test
