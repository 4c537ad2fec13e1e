#include "walk/estimators/vpl_tracer.h"

#include "core/util/parallel_rows.h"
#include "walk/estimators/mirror_pass.h"
#include "walk/estimators/vpl_gather.h"

#include <algorithm>

namespace irad {

namespace {

// What rt-vpl shows at pixel (x, y): the surface the centre ray meets, its L_e plus its VPL sum
// (a mirror: what the VPLs light in it, with `mirrors`; else its L_e alone), or the background.
// Below `traced` roughness the reachable VPLs take the diffuse lobe alone
// (walk/estimators/glossy_pass.h).
glm::vec3 trace_pixel(const Scene& scene, const RayScene& rays, const View& view,
                      const VplSet& vpls, float dmin, float traced, int x, int y, bool mirrors) {
  const CameraRay ray = pixel_ray(view, x, y);
  const glm::vec3 dir = ray.direction;
  const auto hit = rays.intersect(ray.origin, dir, view.znear, 2.0f * view.zfar);
  if (!hit) return background_radiance(scene, dir);
  ShadingPoint p = shading_point(scene, *hit, ray.origin, dir);
  mark_traced_specular(p, traced);
  if (!scene.material_of(hit->triangle).specular)
    return p.emission + gather_vpls(rays, p, vpls, dmin, rays.epsilon());
  if (!mirrors) return p.emission;
  return p.emission +
         mirror_radiance(scene, rays, vpls, hit->triangle, p.position, dir, dmin, rays.epsilon());
}

} // namespace

Image trace_vpls(const Scene& scene, const RayScene& rays, const View& view, const VplSet& vpls,
                 const VplTracerOptions& options) {
  Image image(view.width, view.height);
  const float dmin = options.clamp * scene.bounds.diagonal();
  parallel_rows(view.height, options.threads, [&](int y) {
    for (int x = 0; x < view.width; ++x) {
      if (options.cancel != nullptr && options.cancel->load(std::memory_order_relaxed)) return;
      image.at(x, y) = glm::vec4(
          trace_pixel(scene, rays, view, vpls, dmin, options.traced_roughness, x, y, true), 1.0f);
    }
  });
  return image;
}

void trace_vpl_pixels(const Scene& scene, const RayScene& rays, const View& view,
                      const VplSet& vpls, const VplTracerOptions& options,
                      const std::vector<glm::ivec2>& pixels, Image& image) {
  const float dmin = options.clamp * scene.bounds.diagonal();
  // Chunks of 64 pixels: a shared counter per pixel would cost more than a shadow ray.
  constexpr int chunk = 64;
  const int chunks = static_cast<int>((pixels.size() + chunk - 1) / chunk);
  parallel_rows(chunks, options.threads, [&](int c) {
    const std::size_t end = std::min(pixels.size(), static_cast<std::size_t>(c + 1) * chunk);
    for (std::size_t i = static_cast<std::size_t>(c) * chunk; i < end; ++i) {
      if (options.cancel != nullptr && options.cancel->load(std::memory_order_relaxed)) return;
      const glm::ivec2 p = pixels[i];
      if (p.x < 0 || p.y < 0 || p.x >= view.width || p.y >= view.height) continue;
      const float alpha = image.at(p.x, p.y).a;
      image.at(p.x, p.y) = glm::vec4(
          trace_pixel(scene, rays, view, vpls, dmin, options.traced_roughness, p.x, p.y, false),
          alpha);
    }
  });
}

} // namespace irad
