#include "walk/compensation/screen_compensation.h"

#include "core/lights/clamp_field.h"
#include "core/lights/light_sampler.h"
#include "core/sampling/rng.h"
#include "core/util/error.h"
#include "core/util/parallel_rows.h"
#include "walk/compensation/screen_lookup.h"
#include "walk/estimators/vpl_gather.h"

#include <atomic>
#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

namespace irad {

namespace {

// One gather sample of a pixel with weight (1 - d^2/d(y)^2) > 0: y's value is the image at
// pixel `lookup`, or (lookup < 0) the exactly evaluated `value`. At a glossy x `weight` carries
// x's BRDF factor and y's camera_to (walk/compensation/screen_lookup.h) per channel.
struct GatherSample {
  int lookup = -1;
  glm::vec3 weight{0.0f};
  glm::vec3 value{0.0f};
};

struct PixelSamples {
  glm::vec3 albedo{0.0f}; // rho(x); 1 at a glossy x (its samples' weights hold the BRDF)
  std::vector<GatherSample> samples;
};

// A gather direction at x and its BRDF factor f cos / pdf (the albedo multiplies later at a
// diffuse x: 1): cosine-distributed at a diffuse x, and for the diffuse lobe alone where the
// glossy pass traces the specular one (pi f_d); by the BRDF's sampling at any other glossy x.
struct GatherDirection {
  glm::vec3 w{0.0f};
  glm::vec3 factor{0.0f};
};
std::optional<GatherDirection> gather_direction(const ShadingPoint& x, double u, double v) {
  if (!x.glossy) return GatherDirection{cosine_direction(x.normal, u, v), glm::vec3(1.0f)};
  const GlossyView& g = *x.glossy;
  if (g.traced_specular) {
    const glm::vec3 w = cosine_direction(x.normal, u, v);
    return GatherDirection{w, std::numbers::pi_v<float> * g.brdf.eval_diffuse(g.wo, w)};
  }
  const auto s = g.brdf.sample(g.wo, static_cast<float>(u), static_cast<float>(v));
  if (!s) return std::nullopt;
  return GatherDirection{s->wi, s->weight};
}

struct Context {
  const Scene& scene;
  const RayScene& rays;
  const View& view;
  const VplSet& vpls;
  float dmin; // the global clamp, world units
  float eps;
  bool emission;          // ScreenCompensationOptions::emission
  float traced_roughness; // ScreenCompensationOptions::traced_roughness

  float reach() const { return vpls.clamp_field ? vpls.clamp_field->cap() : dmin; }
  float clamp_at(const glm::vec3& y) const {
    return vpls.clamp_field ? vpls.clamp_field->at(y) : dmin;
  }

  const ScreenLookup* screen = nullptr; // the image's pixel centres
};

void gather_pixel(const Context& c, int px, int py, std::uint32_t count, std::uint64_t seed,
                  PixelSamples& out, ScreenCompensationStats& stats) {
  const PixelCentre& centre = c.screen->centre(px, py);
  if (!centre) return;
  ShadingPoint x = *centre;
  mark_traced_specular(x, c.traced_roughness);
  out.albedo = x.glossy ? glm::vec3(1.0f) : x.albedo;
  Pcg32 rng(mix64(seed ^ (static_cast<std::uint64_t>(py) * c.view.width + px)), 0);
  const glm::vec3 origin = x.position + c.eps * x.geometric;
  for (std::uint32_t s = 0; s < count; ++s) {
    const double u = rng.next_double(), v = rng.next_double();
    const std::optional<GatherDirection> d = gather_direction(x, u, v);
    if (!d) continue;
    const glm::vec3 w = d->w;
    if (glm::dot(w, x.geometric) <= 0.0f) continue;
    ++stats.gathers;
    const auto h = c.rays.intersect(origin, w, 0.0f, c.reach());
    if (!h || c.scene.material_of(h->triangle).specular) continue;
    const ShadingPoint y = shading_point(c.scene, *h, origin, w);
    const float dy = c.clamp_at(y.position);
    const float weight = dy > 0.0f ? 1.0f - h->t * h->t / (dy * dy) : 0.0f;
    if (!(weight > 0.0f)) continue;
    ++stats.in_reach;
    GatherSample g;
    g.weight = x.glossy ? weight * d->factor : glm::vec3(weight);
    g.lookup = c.screen->camera_pixel(y.position, y.geometric);
    if (g.lookup >= 0 && y.glossy) g.weight *= camera_to(y, -w);
    if (g.lookup < 0) {
      ++stats.fallback;
      g.value = (c.emission ? y.emission : glm::vec3(0.0f)) +
                gather_vpls(c.rays, y, c.vpls, c.dmin, c.eps);
    }
    out.samples.push_back(g);
  }
}

} // namespace

Image screen_space_residual(const Scene& scene, const RayScene& rays, const View& view,
                            const VplSet& vpls, const Image& clamped,
                            const ScreenCompensationOptions& options,
                            ScreenCompensationStats* stats) {
  if (clamped.width() != view.width || clamped.height() != view.height)
    throw Error("", "bias compensation", "the image and the view differ in size");
  if (options.iterations < 1) throw Error("", "bias compensation", "needs >= 1 iteration");
  Context c{scene,
            rays,
            view,
            vpls,
            options.clamp * scene.bounds.diagonal(),
            rays.epsilon(),
            options.emission,
            options.traced_roughness,
            nullptr};
  const std::size_t n = std::size_t(view.width) * std::size_t(view.height);
  Image residual(view.width, view.height);
  if (c.reach() <= 0.0f || options.samples == 0) return residual;
  const ScreenLookup screen(scene, rays, view, options.threads);
  c.screen = &screen;

  std::vector<PixelSamples> pixels(n);
  std::vector<ScreenCompensationStats> row_stats(std::size_t(view.height));
  const std::uint64_t seed = mix64(options.seed ^ 0x73637265656eULL);
  parallel_rows(view.height, options.threads, [&](int y) {
    for (int x = 0; x < view.width; ++x)
      gather_pixel(c, x, y, options.samples, seed, pixels[std::size_t(y) * view.width + x],
                   row_stats[std::size_t(y)]);
  });

  // R_{k+1} = rho E[w (image + R_k)(y)]; the fallback samples' values are fixed.
  const float inv_samples = 1.0f / static_cast<float>(options.samples);
  Image next(view.width, view.height);
  for (int k = 0; k < options.iterations; ++k) {
    parallel_rows(view.height, options.threads, [&](int y) {
      for (int x = 0; x < view.width; ++x) {
        const std::size_t i = std::size_t(y) * view.width + x;
        glm::vec3 sum(0.0f);
        for (const GatherSample& g : pixels[i].samples)
          sum +=
              g.weight * (g.lookup < 0 ? g.value
                                       : glm::vec3(clamped.pixels()[std::size_t(g.lookup)]) +
                                             glm::vec3(residual.pixels()[std::size_t(g.lookup)]));
        next.pixels()[i] = glm::vec4(pixels[i].albedo * sum * inv_samples, 0.0f);
      }
    });
    std::swap(residual, next);
  }
  if (stats != nullptr)
    for (const ScreenCompensationStats& r : row_stats) {
      stats->gathers += r.gathers;
      stats->in_reach += r.in_reach;
      stats->fallback += r.fallback;
    }
  return residual;
}

} // namespace irad
