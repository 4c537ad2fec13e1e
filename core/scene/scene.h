#pragma once
// The scene model shared by the walk, the raster and the reference estimators: world-space
// triangles with diffuse materials, emitters, punctual lights and cameras. glTF is one way in.
#include "core/environment/environment.h"
#include "core/scene/bounds.h"
#include "core/scene/texture.h"

#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace irad {

class Animation;

// How a material looks up one of its textures: the TEXCOORD_n set and the KHR_texture_transform
// matrix, uv' = matrix * (u, v, 1) (glTF: translation * rotation * scale, rotation
// counter-clockwise in uv space as the extension defines it).
struct TexCoordMap {
  int texcoord = 0;       // 0: Scene::uvs (TEXCOORD_0), 1: Scene::uvs1 (TEXCOORD_1)
  glm::mat3 matrix{1.0f}; // identity without KHR_texture_transform
  glm::vec2 apply(glm::vec2 uv) const { return glm::vec2(matrix * glm::vec3(uv, 1.0f)); }
};

// glTF alphaMode. Coverage a(x) = base_alpha * texture alpha * COLOR_0 alpha. Mask: the surface
// is there where a >= alpha_cutoff and absent elsewhere (rays, particles, shadow maps and shading
// all pass through it). Blend: a is the probability that a ray or particle stops at the surface.
enum class AlphaMode { Opaque, Mask, Blend };

// Material: the glTF 2.0 metallic-roughness BRDF (design.md section 1b; evaluated by
// core/material/brdf.h) with base = base_color * texture(uv) * COLOR_0 (linear), emitted radiance
// L_e(x) = emission * emissive_texture(uv), Lambertian, from the front face only unless
// double_sided. The front face is the one whose vertices run counter-clockwise (glTF).
// The defaults of this struct declare a Lambertian surface (metallic 0, specular_factor 0:
// f_r = base/pi exactly); the glTF reader sets the file's values, whose defaults are metallic 1,
// roughness 1, specular 1.
// specular: a perfect mirror (seed section 5.1.2; core/scene/mirrors.h) on both faces, whose
// reflectance is base_color * texture(uv); it reflects no light diffusely.
struct Material {
  std::string name;
  glm::vec3 base_color{1.0f};
  int base_color_texture = -1; // index into Scene::textures, or -1
  glm::vec3 emission{0.0f};    // emissiveFactor * KHR_materials_emissive_strength
  int emissive_texture = -1;
  bool double_sided = false;
  bool specular = false;
  TexCoordMap base_color_map; // how base_color_texture is looked up
  TexCoordMap emissive_map;   // how emissive_texture is looked up
  AlphaMode alpha_mode = AlphaMode::Opaque;
  float alpha_cutoff = 0.5f; // Mask only
  float base_alpha = 1.0f;   // baseColorFactor's alpha

  // Metallic m and perceptual roughness r (alpha = r^2): factor * metallicRoughnessTexture's B
  // (m) and G (r) channels.
  float metallic = 0.0f;
  float roughness = 1.0f;
  int metallic_roughness_texture = -1;
  TexCoordMap metallic_roughness_map;
  // Dielectric Fresnel: f0 = ((ior - 1)/(ior + 1))^2 (KHR_materials_ior), scaled by
  // KHR_materials_specular: f0 = min(f0 * specular_color, 1) * s, f90 = s with s = specular_factor
  // * specular_texture's alpha, specular_color = its factor * specular_color_texture's rgb.
  float ior = 1.5f;
  float specular_factor = 0.0f;
  int specular_texture = -1;
  TexCoordMap specular_map;
  glm::vec3 specular_color{1.0f};
  int specular_color_texture = -1;
  TexCoordMap specular_color_map;
  // Tangent-space normal map (linear texels, n = 2 t - 1, x and y scaled by normal_scale), or -1.
  int normal_texture = -1;
  TexCoordMap normal_map;
  float normal_scale = 1.0f;

  // Lambertian by declaration (design.md 1b): metallic 0 and specular 0 make F0 = F90 = 0, so
  // f_r = base/pi whatever the textures say; the estimators take their diffuse paths for it.
  bool lambertian() const { return metallic == 0.0f && specular_factor == 0.0f; }
  bool emissive() const { return emission.x > 0.0f || emission.y > 0.0f || emission.z > 0.0f; }
};

// Pinhole camera, or orthographic (parallel rays along -z through a (2 xmag) x (2 ymag)
// rectangle). camera_to_world maps the camera frame (looking down -z, y up) to the world.
struct Camera {
  std::string name;
  glm::mat4 camera_to_world{1.0f};
  bool orthographic = false;
  float xmag = 1.0f;           // orthographic only: half width and half height of the view, in
  float ymag = 1.0f;           // scene units (aspect = xmag / ymag)
  float yfov = 0.6911f;        // radians, perspective only
  std::optional<float> aspect; // width / height, if the file fixes it
  float znear = 0.0f;          // 0: derived from the scene's scale
  std::optional<float> zfar;

  glm::vec3 position() const { return glm::vec3(camera_to_world[3]); }
};

// KHR_lights_punctual light, placed in the world. intensity = color * intensity of the file and is
// a radiant intensity in the image's linear units per steradian (no photometric conversion); for
// a directional light it is the irradiance E on a surface facing the light (units per m^2 of the
// scene's length unit), and only `direction` (where the light travels) matters.
struct PunctualLight {
  enum class Kind { Point, Spot, Directional };
  std::string name;
  Kind kind = Kind::Point;
  glm::vec3 position{0.0f};
  glm::vec3 direction{0.0f, 0.0f, -1.0f}; // spot axis, or the directional light's travel (unit)
  glm::vec3 intensity{0.0f};
  float inner_cone = 0.0f; // radians, spot only
  float outer_cone = 0.7853982f;
  // Directional only: the angular radius r (radians) of the disk camera rays see toward the
  // light (a sun), of uniform radiance E / (pi sin^2 r); 0: not visible. Lighting is unchanged:
  // the light stays a delta in direction for every estimator.
  float angular_radius = 0.0f;
};

struct Scene {
  std::string source; // path of the file it came from, for messages

  // Triangle soup in world space. Vertex arrays run in parallel; normals are unit length.
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec2> uvs;    // empty when no primitive has TEXCOORD_0
  std::vector<glm::vec2> uvs1;   // TEXCOORD_1; empty unless some texture of a material uses it
  std::vector<glm::vec4> colors; // COLOR_0 (linear RGBA, 1 where a primitive has none); empty
                                 // when no primitive has it. albedo *= rgb, coverage *= alpha.
  // TANGENT (xyz unit, w = +-1: bitangent = w cross(normal, tangent)), from the file or generated
  // (core/mesh/tangents.h); empty unless some material has a normal map.
  std::vector<glm::vec4> tangents;
  std::vector<glm::uvec3> triangles;
  std::vector<std::uint32_t> triangle_material; // one per triangle

  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::vector<Camera> cameras;
  std::vector<PunctualLight> lights;
  // Distant light around the scene (core/environment/environment.h), or nullptr: none (black
  // background).
  std::shared_ptr<const Environment> environment;

  Bounds bounds; // of all triangles (over the whole animation when there is one)

  // glTF node animation (core/animation/animation.h), or nullptr for a static scene.
  // Animation::pose moves this scene's triangles, cameras and lights to a time.
  std::shared_ptr<const Animation> animation;

  std::size_t triangle_count() const { return triangles.size(); }
  const Material& material_of(std::size_t triangle) const {
    return materials[triangle_material[triangle]];
  }
  bool has_emitters() const;
  bool has_environment() const { return environment && !environment->black(); }
  bool has_textures() const { return !textures.empty(); }
  bool has_specular() const;   // any material is a mirror
  bool all_lambertian() const; // every material is a mirror or Material::lambertian()
};

// The camera_to_world of a camera on a node with world matrix `world`: the right-handed rotation
// whose z axis is world's z direction and whose y axis is world's y made orthogonal to it (scale
// and shear dropped), at world's translation; nullopt when those axes are degenerate.
std::optional<glm::mat4> camera_frame_of(const glm::dmat4& world);

// A point of triangle t at barycentrics (b1, b2) (the weights of vertices 1 and 2).
struct SurfacePoint {
  glm::vec3 position;
  glm::vec3 geometric_normal; // unit, the front (counter-clockwise) side
  glm::vec3 shading_normal;   // interpolated NORMAL, unit (the geometric one where it vanishes),
                              // after the material's normal map (core/material/surface_material.h)
};
SurfacePoint surface_at(const Scene& scene, std::size_t t, glm::vec2 bary);

// Surface albedo and emission at a point of triangle t with barycentrics (b1, b2): factor *
// texture(M (uv_n, 1)) with the material's TexCoordMap (set n, matrix M); the albedo also times
// COLOR_0's rgb (glTF: vertex colours scale the base colour, not the emission).
glm::vec3 albedo_at(const Scene& scene, std::size_t t, glm::vec2 bary);
// The texel of `texture` that `map` selects at a point of triangle t: texture(M (uv_n, 1)) with
// uv_n interpolated from the map's TEXCOORD set; nullopt when the texture or the set is absent.
std::optional<glm::vec4> texture_at(const Scene& scene, std::size_t t, glm::vec2 bary, int texture,
                                    const TexCoordMap& map);
// Whether the scene has the TEXCOORD set `map` reads.
bool has_texcoords(const Scene& scene, const TexCoordMap& map);
// COLOR_0 at a point of triangle t, or 1 when the scene has no vertex colours.
glm::vec4 vertex_color_at(const Scene& scene, std::size_t t, glm::vec2 bary);
glm::vec3 emission_at(const Scene& scene, std::size_t t, glm::vec2 bary);
// Coverage a(x) = base_alpha * base texture alpha (through base_color_map) * COLOR_0 alpha at a
// point of triangle t, for Mask and Blend materials; 1 for Opaque ones (glTF ignores alpha there).
// The one definition the walk, the CPU estimators and the raster share.
float coverage_at(const Scene& scene, std::size_t t, glm::vec2 bary);
// Whether a surface of `material` with coverage a is there for a ray or particle that draws
// u in [0, 1): Opaque always; Mask iff a >= alpha_cutoff; Blend iff u < a (probability a).
bool covered(const Material& material, float coverage, float u);
// Area-weighted mean albedo: rho_bar = sum(mean(rho_k) A_k) / sum(A_k) over all triangles, with
// textured albedos taken at their texel mean and COLOR_0 at the triangle's centroid. rho_k is the
// base colour of a Lambertian material or a mirror, else the BRDF's hemispherical albedo
// (core/material/brdf.h, specular lobe included). Time linear in triangles plus texels: each
// texture's mean is taken once, and each material's albedo once (per triangle only for a BRDF
// under COLOR_0).
double mean_albedo(const Scene& scene);
// Triangle t's emission with its texture at the texel mean (emitter powers): emission_at's rule,
// so a texture whose TEXCOORD set the scene lacks counts as absent in both.
glm::vec3 mean_emission(const Scene& scene, std::size_t t);
float triangle_area(const Scene& scene, std::size_t t);
// What a camera ray along unit w that meets no surface sees: 0 when the scene's environment is
// not visible (Environment::visible false); else L_env(w) (0 without an environment) plus the
// radiance E / (pi sin^2 r) of every directional light of angular radius r > 0 (a sun) whose
// disk holds w. The one definition pt, rt-vpl and the raster's background pass
// (raster/passes/background.h) share. Rays after a mirror see the environment whatever `visible`
// says, and no sun disk (it is a delta light for the lighting).
glm::vec3 background_radiance(const Scene& scene, const glm::vec3& w);
// Radiance of a sun's disk (PunctualLight::angular_radius > 0), 0 otherwise.
glm::vec3 sun_disk_radiance(const PunctualLight& light);
glm::vec3 geometric_normal(const Scene& scene, std::size_t t); // unit, front-facing side

} // namespace irad
