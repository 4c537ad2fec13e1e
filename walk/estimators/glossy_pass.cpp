#include "walk/estimators/glossy_pass.h"

#include "core/environment/environment.h"
#include "core/sampling/rng.h"
#include "core/util/parallel_rows.h"
#include "walk/compensation/screen_lookup.h"
#include "walk/estimators/mirror_pass.h"
#include "walk/estimators/vpl_gather.h"

#include <algorithm>
#include <limits>
#include <vector>

namespace irad {

namespace {

struct GlossyContext {
  const Scene& scene;
  const RayScene& rays;
  const VplSet& vpls;
  const ScreenLookup& screen;
  const Image& before; // the VPL estimator's image, read at the hits the camera sees
  const GlossyPassOptions& options;
  float dmin, eps;
  std::vector<double> cdf; // running sums of the VPLs' sampling weights (sampled_gather)
};

// A VPL's weight in sampled_gather: the luminance of its intensity.
double sampling_weight(const Vpl& v) {
  return glm::max(0.0, double(luminance(v.intensity)));
}

// VPLs drawn per hit the camera does not see.
constexpr std::uint32_t kHiddenVpls = 32;

// gather_vpls at y estimated from kHiddenVpls VPLs drawn by sampling_weight, each term over
// kHiddenVpls times its probability: unbiased, at a fixed cost per hit whatever the number of
// VPLs (every VPL with fewer than that).
glm::vec3 sampled_gather(const GlossyContext& c, const ShadingPoint& y, Pcg32& rng) {
  const std::size_t n = c.vpls.vpls.size();
  if (n <= kHiddenVpls) return gather_vpls(c.rays, y, c.vpls, c.dmin, c.eps);
  const double total = c.cdf.back();
  if (!(total > 0.0)) return glm::vec3(0.0f);
  glm::vec3 sum(0.0f);
  for (std::uint32_t k = 0; k < kHiddenVpls; ++k) {
    const double u = rng.next_double() * total;
    const auto j =
        static_cast<std::size_t>(std::upper_bound(c.cdf.begin(), c.cdf.end(), u) - c.cdf.begin());
    if (j >= n) continue;
    const double p = (c.cdf[j] - (j > 0 ? c.cdf[j - 1] : 0.0)) / total;
    const Vpl& v = c.vpls.vpls[j];
    const glm::vec3 term = vpl_irradiance(c.rays, y, v, c.vpls, c.dmin, c.eps);
    if (term != glm::vec3(0.0f)) sum += term * receiver_brdf(y, v) / static_cast<float>(p);
  }
  return sum / static_cast<float>(kHiddenVpls);
}

glm::vec3 incoming(const GlossyContext& c, const glm::vec3& origin, const glm::vec3& dir,
                   Pcg32& rng, GlossyPassStats& stats, int depth);

// One direction of x's specular lobe from (u0, u1), its weight times L along it (incoming at
// `depth`); 0 where the sample falls below x's surface.
glm::vec3 specular_sample(const GlossyContext& c, const ShadingPoint& x, float u0, float u1,
                          Pcg32& rng, GlossyPassStats& stats, int depth) {
  const auto sample = x.glossy->brdf.sample_specular(x.glossy->wo, u0, u1);
  if (!sample || !(glm::dot(sample->wi, x.geometric) > 0.0f)) return glm::vec3(0.0f);
  ++stats.rays;
  return sample->weight *
         incoming(c, x.position + c.eps * x.geometric, sample->wi, rng, stats, depth);
}

// L(y -> x) of a narrow-lobe y the ray met after `depth` narrow lobes: its diffuse lobe (and the
// lights' VPLs through the whole BRDF) from sampled_gather, its specular lobe by one more ray
// (incoming), the whole BRDF from the VPLs past GlossyPassOptions::bounces.
glm::vec3 narrow_lobe_light(const GlossyContext& c, ShadingPoint y, Pcg32& rng,
                            GlossyPassStats& stats, int depth) {
  if (depth >= c.options.bounces) return sampled_gather(c, y, rng);
  mark_traced_specular(y, c.options.roughness);
  const glm::vec3 diffuse = sampled_gather(c, y, rng);
  const float u0 = static_cast<float>(rng.next_double());
  const float u1 = static_cast<float>(rng.next_double());
  return diffuse + specular_sample(c, y, u0, u1, rng, stats, depth + 1);
}

// L(y -> x) along the ray origin + t dir (glossy_pass.h's cases); depth: the narrow lobes the
// light has met since the camera's.
glm::vec3 incoming(const GlossyContext& c, const glm::vec3& origin, const glm::vec3& dir,
                   Pcg32& rng, GlossyPassStats& stats, int depth) {
  const auto hit = c.rays.intersect(origin, dir, 0.0f, std::numeric_limits<float>::infinity());
  if (!hit)
    return c.options.environment && c.scene.has_environment() ? c.scene.environment->radiance(dir)
                                                              : glm::vec3(0.0f);
  if (c.scene.material_of(hit->triangle).specular)
    return mirror_radiance(c.scene, c.rays, c.vpls, hit->triangle, origin + hit->t * dir, dir,
                           c.dmin, c.eps);
  const ShadingPoint y = shading_point(c.scene, *hit, origin, dir);
  // A narrow-lobe y's pixel holds its diffuse lobe alone.
  if (narrow_lobe(y, c.options.roughness)) {
    ++stats.exact;
    return narrow_lobe_light(c, y, rng, stats, depth);
  }
  const int pixel = c.screen.camera_pixel(y.position, y.geometric);
  if (pixel < 0) {
    ++stats.exact;
    return sampled_gather(c, y, rng);
  }
  ++stats.on_screen;
  const glm::vec3 shown(c.before.pixels()[static_cast<std::size_t>(pixel)]);
  return glm::max(shown - y.emission, glm::vec3(0.0f)) * camera_to(y, -dir);
}

// The mean of `samples` specular directions' weight times L at pixel (px, py), 0 where the pixel
// does not see a narrow lobe.
glm::vec3 specular_light(const GlossyContext& c, int px, int py, GlossyPassStats& stats) {
  const PixelCentre& centre = c.screen.centre(px, py);
  if (!centre || !narrow_lobe(*centre, c.options.roughness)) return glm::vec3(0.0f);
  const ShadingPoint& x = *centre;
  ++stats.pixels;
  const std::uint64_t index =
      static_cast<std::uint64_t>(py) * static_cast<std::uint64_t>(c.screen.width()) +
      static_cast<std::uint64_t>(px);
  Pcg32 rng(mix64(c.options.seed ^ 0x676c6f7373ULL ^ mix64(index)), 0);
  glm::vec3 sum(0.0f);
  const auto n = static_cast<float>(c.options.samples);
  for (std::uint32_t s = 0; s < c.options.samples; ++s) {
    // Stratified in u0 (the visible normal's radius), random in u1.
    const float u0 = (static_cast<float>(s) + static_cast<float>(rng.next_double())) / n;
    const float u1 = static_cast<float>(rng.next_double());
    sum += specular_sample(c, x, u0, u1, rng, stats, 0);
  }
  return sum / n;
}

} // namespace

void add_glossy_pass(const Scene& scene, const RayScene& rays, const View& view, const VplSet& vpls,
                     const GlossyPassOptions& options, Image& image, GlossyPassStats* stats) {
  if (!(options.roughness > 0.0f) || options.samples == 0 || scene.all_lambertian()) return;
  const ScreenLookup screen(scene, rays, view, options.threads);
  const Image before = image;
  GlossyContext c{
      scene,          rays, vpls, screen, before, options, options.clamp * scene.bounds.diagonal(),
      rays.epsilon(), {}};
  double total = 0.0;
  for (const Vpl& v : vpls.vpls) {
    total += sampling_weight(v);
    c.cdf.push_back(total);
  }
  std::vector<GlossyPassStats> row_stats(static_cast<std::size_t>(view.height));
  parallel_rows(view.height, options.threads, [&](int y) {
    for (int x = 0; x < view.width; ++x) {
      if (options.cancel != nullptr && options.cancel->load(std::memory_order_relaxed)) return;
      const glm::vec3 l = specular_light(c, x, y, row_stats[static_cast<std::size_t>(y)]);
      image.at(x, y) += glm::vec4(l, 0.0f);
    }
  });
  if (stats == nullptr) return;
  for (const GlossyPassStats& r : row_stats) {
    stats->pixels += r.pixels;
    stats->rays += r.rays;
    stats->on_screen += r.on_screen;
    stats->exact += r.exact;
  }
}

} // namespace irad
