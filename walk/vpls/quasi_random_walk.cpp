#include "walk/vpls/quasi_random_walk.h"

#include "core/lights/light_sampler.h"
#include "core/material/surface_material.h"
#include "core/sampling/particle_counts.h"
#include "core/sampling/radical_inverse.h"
#include "core/util/error.h"
#include "walk/rays/alpha.h"
#include "walk/rays/mirror_walk.h"

#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <optional>

namespace irad {

// The surface seen by a path vertex: position, normals facing the side the particle came from,
// and the BRDF's inputs where the material is not Lambertian.
struct PathVertex {
  glm::vec3 position;
  glm::vec3 normal; // shading
  glm::vec3 albedo;
  glm::vec3 geometric;
  std::optional<BrdfInputs> glossy;
};

namespace {

PathVertex vertex_at(const Scene& scene, const RayHit& hit, const glm::vec3& incoming) {
  const SurfacePoint sp = surface_at(scene, hit.triangle, hit.bary);
  glm::vec3 ng = sp.geometric_normal;
  if (glm::dot(ng, incoming) > 0.0f) ng = -ng; // face the arriving particle
  glm::vec3 ns = sp.shading_normal;
  if (glm::dot(ns, ng) < 0.0f) ns = -ns;  // same side as the geometric normal
  if (glm::dot(ns, ng) <= 1e-3f) ns = ng; // shading normal unusable near the tangent plane
  PathVertex y{sp.position, ns, albedo_at(scene, hit.triangle, hit.bary), ng, std::nullopt};
  const Material& m = scene.material_of(hit.triangle);
  if (!m.lambertian() && !m.specular) y.glossy = brdf_inputs_at(scene, hit.triangle, hit.bary);
  return y;
}

bool positive(const glm::vec3& v) {
  return v.x > 0.0f || v.y > 0.0f || v.z > 0.0f;
}

Vpl light_vpl(const LightStart& start, float weight, std::uint32_t path) {
  Vpl v;
  v.position = start.position;
  v.normal = start.normal;
  v.intensity = weight * start.beta;
  v.kind = start.kind;
  v.environment = start.environment;
  v.depth = 0;
  v.path = path;
  v.cos_inner = start.cos_inner;
  v.cos_outer = start.cos_outer;
  return v;
}

// The VPL at reflection j of particle i: a one-sided surface point.
Vpl surface_vpl(const glm::vec3& position, const glm::vec3& normal, const glm::vec3& intensity,
                int j, std::uint32_t i) {
  Vpl v;
  v.position = position;
  v.normal = normal;
  v.intensity = intensity;
  v.kind = VplKind::Surface;
  v.depth = static_cast<std::uint16_t>(j);
  v.path = i;
  return v;
}

void warn_capped(const ParticleCounts& counts, Log& log, int cap) {
  if (counts.capped())
    log.warn(fmt::format("mean albedo rho_bar = {:.4f} is close to or above 1: the walk is capped "
                         "at {} reflections (light beyond them is lost)",
                         counts.rho_bar(), cap));
}

} // namespace

QuasiRandomWalk::QuasiRandomWalk(const Scene& scene, const RayScene& rays,
                                 const WalkOptions& options, Log& log)
    : scene_(&scene), rays_(&rays), lights_(scene, options.allocation),
      counts_(options.paths == 0 ? throw Error("", "--paths", "must be at least 1") : options.paths,
              mean_albedo(scene), options.depth_cap),
      halton_(options.sequence, 2 * static_cast<std::size_t>(counts_.l_max()) + 2, options.seed),
      mirrors_(find_mirrors(scene)) {
  if (lights_.empty())
    throw Error(scene.source, "",
                "no light: no emissive surface, no punctual light and no environment");
  warn_capped(counts_, log, options.depth_cap);
}

void QuasiRandomWalk::trace(std::uint32_t i, std::vector<Vpl>& out,
                            std::vector<VplLobe>* lobes) const {
  const Scene& scene = *scene_;
  const float eps = rays_->epsilon();
  const float far = std::numeric_limits<float>::infinity();
  const int depth = counts_.depth_of(i);
  const std::uint32_t h = halton_index(i);
  LightStart start = lights_.sample(scene, halton_.sample(0, h), halton_.sample(1, h));
  start.beta *= light_presence(scene, start); // walk/rays/alpha.h: 0 on a cut-out, a on Blend
  if (!positive(start.beta)) return;
  out.push_back(light_vpl(start, 1.0f / static_cast<float>(counts_.reaching(0)), i));
  if (!mirrors_.empty()) append_mirrored(out.back(), mirrors_, out);
  if (depth == 0) return;

  // Leave the light: beta_1 = beta_0 * profile / pdf.
  const LightDirection leave = lights_.direction(start, halton_.sample(2, h), halton_.sample(3, h));
  glm::vec3 beta = start.beta * leave.factor;
  glm::vec3 origin = leave.origin;
  glm::vec3 dir = leave.direction;
  glm::vec3 offset_normal = start.triangle >= 0 ? start.normal : glm::vec3(0.0f);
  if (glm::dot(offset_normal, dir) < 0.0f) offset_normal = -offset_normal;
  for (int j = 1; j <= depth && positive(beta); ++j) {
    // Mirrors (core/scene/mirrors.h) reflect the particle on to the next diffuse surface (beta *=
    // R); a specular bounce is not a reflection j (it takes no Halton dimensions).
    glm::vec3 from = origin + eps * offset_normal;
    const auto hit = mirrors_.empty() ? rays_->intersect(from, dir, 0.0f, far)
                                      : trace_through_mirrors(scene, *rays_, from, dir, beta, eps);
    if (!hit) return; // the particle leaves the scene
    const PathVertex y = vertex_at(scene, *hit, dir);
    if (y.glossy) {
      if (!glossy_vertex(y, i, j, depth, beta, dir, out, lobes)) return;
      origin = y.position;
      offset_normal = y.normal;
      continue;
    }
    const glm::vec3 radiant =
        beta * y.albedo * std::numbers::inv_pi_v<float>; // beta_j rho(y_j) / pi
    if (!positive(radiant)) return;                      // absorbed: nothing further
    const Vpl v = surface_vpl(y.position, y.normal, radiant / float(counts_.reaching(j)), j, i);
    out.push_back(v);
    if (!mirrors_.empty()) append_mirrored(v, mirrors_, out);
    if (j == depth) return;
    // Scatter: cosine-distributed from (Phi_{b_{2j+2}}(i), Phi_{b_{2j+3}}(i)); beta_{j+1} =
    // rho(y_j) beta_j.
    dir = cosine_direction(y.normal, halton_.sample(2 * j + 2, h), halton_.sample(2 * j + 3, h));
    beta *= y.albedo;
    origin = y.position;
    offset_normal = y.normal;
  }
}

bool QuasiRandomWalk::glossy_vertex(const PathVertex& y, std::uint32_t i, int j, int depth,
                                    glm::vec3& beta, glm::vec3& dir, std::vector<Vpl>& out,
                                    std::vector<VplLobe>* lobes) const {
  const glm::vec3 incident = -dir;
  const Brdf brdf(*y.glossy, facing_normal(y.normal, incident));
  const glm::vec3 a = brdf.albedo(incident);
  const glm::vec3 radiant = beta * a * std::numbers::inv_pi_v<float>; // beta_j a(incident) / pi
  if (!positive(radiant)) return false;
  // The VPL's normal is the lobe's.
  Vpl v = surface_vpl(y.position, brdf.normal(), radiant / float(counts_.reaching(j)), j, i);
  if (lobes != nullptr) {
    v.lobe = static_cast<std::int32_t>(lobes->size());
    lobes->push_back({*y.glossy, incident, a});
  }
  out.push_back(v);
  if (!mirrors_.empty()) append_mirrored(v, mirrors_, out);
  if (j == depth) return false;
  // Scatter by the BRDF from the same Halton pair: beta_{j+1} = beta_j f_r cos / pdf.
  const std::uint32_t h = halton_index(i);
  const std::optional<BrdfSample> s =
      brdf.sample(incident, static_cast<float>(halton_.sample(2 * j + 2, h)),
                  static_cast<float>(halton_.sample(2 * j + 3, h)));
  if (!s || glm::dot(s->wi, y.geometric) <= 0.0f) return false;
  dir = s->wi;
  beta *= s->weight;
  return true;
}

VplSet QuasiRandomWalk::header() const {
  VplSet set;
  set.paths = counts_.paths();
  set.rho_bar = counts_.rho_bar();
  set.l_max = counts_.l_max();
  set.depth_capped = counts_.capped();
  set.planned = counts_.vpl_count();
  set.mirrors = mirrors_;
  return set;
}

VplSet quasi_random_walk(const Scene& scene, const RayScene& rays, const WalkOptions& options,
                         Log& log) {
  const QuasiRandomWalk walk(scene, rays, options, log);
  VplSet set = walk.header();
  set.vpls.reserve(set.planned);
  const std::uint32_t end = options.end_path == 0 ? set.paths : options.end_path;
  if (options.first_path >= end || end > set.paths)
    throw Error("", "--path-range",
                fmt::format("{}:{} is not a non-empty range within 0:{}", options.first_path, end,
                            set.paths));
  for (std::uint32_t i = options.first_path; i < end; ++i) walk.trace(i, set.vpls, &set.lobes);
  return set;
}

} // namespace irad
