#include "walk/estimators/mirror_pass.h"

#include "core/util/parallel_rows.h"
#include "walk/estimators/vpl_gather.h"
#include "walk/rays/mirror_walk.h"

namespace irad {

glm::vec3 mirror_radiance(const Scene& scene, const RayScene& rays, const VplSet& vpls,
                          std::size_t triangle, const glm::vec3& position, const glm::vec3& dir,
                          float dmin, float eps) {
  glm::vec3 n = geometric_normal(scene, triangle);
  if (glm::dot(n, dir) > 0.0f) n = -n; // the side the ray arrived from
  glm::vec3 throughput = scene.material_of(triangle).base_color;
  glm::vec3 origin = position + eps * n;
  glm::vec3 reflected = reflect_direction(n, dir);
  const auto hit = trace_through_mirrors(scene, rays, origin, reflected, throughput, eps);
  if (!hit) // the environment, whether or not camera rays see it (core/scene/scene.h)
    return scene.has_environment() ? throughput * scene.environment->radiance(reflected)
                                   : glm::vec3(0.0f);
  const ShadingPoint x = shading_point(scene, *hit, origin, reflected);
  return throughput * (x.emission + gather_vpls(rays, x, vpls, dmin, eps));
}

void add_mirror_pass(const Scene& scene, const RayScene& rays, const View& view, const VplSet& vpls,
                     const MirrorPassOptions& options, Image& image) {
  if (!scene.has_specular()) return;
  const float dmin = options.clamp * scene.bounds.diagonal();
  const float eps = rays.epsilon();
  parallel_rows(view.height, options.threads, [&](int y) {
    for (int x = 0; x < view.width; ++x) {
      if (options.cancel != nullptr && options.cancel->load(std::memory_order_relaxed)) return;
      const CameraRay ray = pixel_ray(view, x, y);
      const glm::vec3 dir = ray.direction;
      const auto hit = rays.intersect(ray.origin, dir, view.znear, 2.0f * view.zfar);
      if (!hit || !scene.material_of(hit->triangle).specular) continue;
      const glm::vec3 c = mirror_radiance(scene, rays, vpls, hit->triangle,
                                          ray.origin + hit->t * dir, dir, dmin, eps);
      image.at(x, y) += glm::vec4(c, 0.0f);
    }
  });
}

} // namespace irad
