#include "walk/vpl_tracer.h"

#include "core/parallel_rows.h"
#include "walk/mirror_pass.h"
#include "walk/vpl_gather.h"

namespace irad {

Image trace_vpls(const Scene& scene, const RayScene& rays, const View& view, const VplSet& vpls,
                 const VplTracerOptions& options) {
  Image image(view.width, view.height);
  const float dmin = options.clamp * scene.bounds.diagonal();
  const float eps = rays.epsilon();
  parallel_rows(view.height, options.threads, [&](int y) {
    for (int x = 0; x < view.width; ++x) {
      if (options.cancel != nullptr && options.cancel->load(std::memory_order_relaxed)) return;
      const CameraRay ray = pixel_ray(view, x, y);
      const glm::vec3 dir = ray.direction;
      glm::vec3 c(0.0f);
      if (const auto hit = rays.intersect(ray.origin, dir, view.znear, 2.0f * view.zfar)) {
        const ShadingPoint p = shading_point(scene, *hit, ray.origin, dir);
        c = p.emission +
            (scene.material_of(hit->triangle).specular
                 ? mirror_radiance(scene, rays, vpls, hit->triangle, p.position, dir, dmin, eps)
                 : gather_vpls(rays, p, vpls, dmin, eps));
      } else {
        c = background_radiance(scene, dir);
      }
      image.at(x, y) = glm::vec4(c, 1.0f);
    }
  });
  return image;
}

} // namespace irad
