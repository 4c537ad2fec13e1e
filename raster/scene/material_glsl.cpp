#include "raster/scene/material_glsl.h"

#include "raster/passes/vpl_shader.h"

#include <glm/gtc/type_ptr.hpp>
#include <stdexcept>
#include <string>

namespace irad::gl {

namespace {

constexpr const char* kVertexMarker = "#pragma irad_material_vertex\n";
constexpr const char* kFragmentMarker = "#pragma irad_material_fragment\n";

// Vertex stage: the material's attributes handed on unchanged.
constexpr const char* kVertexGlsl = R"(layout(location = 2) in vec2 a_uv;
out vec2 v_uv;
#ifdef IRAD_UV1
layout(location = 3) in vec2 a_uv1;
out vec2 v_uv1;
#endif
#ifdef IRAD_COLOR
layout(location = 4) in vec4 a_color;
out vec4 v_color;
#endif
#ifdef IRAD_NORMAL_MAP
layout(location = 5) in vec4 a_tangent;
out vec4 v_tangent;
#endif
void copy_material_attributes() {
  v_uv = a_uv;
#ifdef IRAD_UV1
  v_uv1 = a_uv1;
#endif
#ifdef IRAD_COLOR
  v_color = a_color;
#endif
#ifdef IRAD_NORMAL_MAP
  v_tangent = a_tangent;
#endif
}
)";

// Fragment stage. material_uv: uv' = M (uv_n, 1) with the map's set n (core/scene/scene.h
// TexCoordMap). Albedo rho = base_color * texture(uv').rgb * COLOR_0.rgb; emission L_e = emission *
// emissive_texture(uv').rgb (COLOR_0 does not scale it: glTF).
//
// Alpha (core/scene/scene.h coverage_at, covered): a = base_alpha * texture(uv').a * COLOR_0.a.
// Mask: the fragment is absent where a < alpha_cutoff. Blend: absent unless h < a, h in [0, 1) a
// hash of a key. Camera passes key on the fragment's world point (its float bits less the 10 lowest
// mantissa bits: cells of ~1e-4 of the coordinate) and the primitive, so every camera pass of a
// frame (depth, G-buffer, emitters, each VPL's shading, and the k x k tiles of interleaved
// sampling, which reach the same points through other matrices: all but the pixels within a
// rounding error of a cell's edge) agrees on which surface a pixel sees. Shadow passes key on the
// shadow texel, the primitive and the VPL's position, so each VPL sees its own random subset of the
// surface. The hash is deterministic and about uniform, so over many pixels or VPLs the expected
// image is that of a surface of opacity a. Cost: a scene with a Mask or Blend material compiles
// every pass with IRAD_ALPHA; its opaque materials then pay one uniform branch per fragment
// (u_alpha_mode 0) and their coverage-only passes draw material by material instead of in one call.
constexpr const char* kFragmentGlsl = R"(in vec2 v_uv;
#ifdef IRAD_UV1
in vec2 v_uv1;
#endif
#ifdef IRAD_COLOR
in vec4 v_color;
#endif
uniform vec3 u_base_color;
uniform bool u_has_base_texture;
uniform sampler2D u_base_texture;
uniform mat3 u_base_map;
uniform int u_base_set;
uniform vec3 u_emission;
uniform bool u_has_emissive_texture;
uniform sampler2D u_emissive_texture;
uniform mat3 u_emissive_map;
uniform int u_emissive_set;
vec2 material_uv(mat3 m, int set) {
#ifdef IRAD_UV1
  vec2 uv = set == 1 ? v_uv1 : v_uv;
#else
  vec2 uv = v_uv;
#endif
  return (m * vec3(uv, 1.0)).xy;
}
vec4 material_base_texel() { // the base colour texture through its uv set and transform
  return texture(u_base_texture, material_uv(u_base_map, u_base_set));
}
vec3 material_albedo() {
  vec3 albedo = u_base_color;
  if (u_has_base_texture) albedo *= material_base_texel().rgb;
#ifdef IRAD_COLOR
  albedo *= v_color.rgb;
#endif
  return albedo;
}
vec3 material_emission() {
  vec3 le = u_emission;
  if (u_has_emissive_texture)
    le *= texture(u_emissive_texture, material_uv(u_emissive_map, u_emissive_set)).rgb;
  return le;
}
#ifdef IRAD_NORMAL_MAP
in vec4 v_tangent;
uniform bool u_has_normal_texture;
uniform sampler2D u_normal_texture;
uniform mat3 u_normal_map;
uniform int u_normal_set;
uniform float u_normal_scale;
#endif
// The shading normal after the normal map (core/material/surface_material.h mapped_normal), from
// the unit interpolated normal n.
vec3 material_normal(vec3 n) {
#ifdef IRAD_NORMAL_MAP
  if (!u_has_normal_texture) return n;
  vec3 t = v_tangent.xyz - dot(v_tangent.xyz, n) * n;
  float len = length(t);
  if (!(len > 1e-6)) return n;
  t /= len;
  vec3 b = (v_tangent.w < 0.0 ? -1.0 : 1.0) * cross(n, t);
  vec3 c = 2.0 * texture(u_normal_texture, material_uv(u_normal_map, u_normal_set)).xyz - 1.0;
  c.xy *= u_normal_scale;
  vec3 o = c.x * t + c.y * b + c.z * n;
  float o_len = length(o);
  return o_len > 1e-6 ? o / o_len : n;
#else
  return n;
#endif
}
#ifdef IRAD_GLOSSY
uniform bool u_lambertian;   // Material::lambertian() or a mirror: m = f0 = f90 = 0
uniform float u_metallic;
uniform float u_roughness;
uniform bool u_has_mr_texture;
uniform sampler2D u_mr_texture;
uniform mat3 u_mr_map;
uniform int u_mr_set;
uniform vec3 u_f0;           // ((ior - 1)/(ior + 1))^2 specular_color
uniform float u_specular;    // specular_factor
uniform bool u_has_specular_texture;
uniform sampler2D u_specular_texture;
uniform mat3 u_specular_map;
uniform int u_specular_set;
uniform bool u_has_specular_color_texture;
uniform sampler2D u_specular_color_texture;
uniform mat3 u_specular_color_map;
uniform int u_specular_color_set;
// The BRDF's inputs but the base colour (core/material/surface_material.h brdf_inputs_at):
// m = metallic x texture B, r = roughness x texture G, s = specular x texture alpha,
// f0 = min(u_f0 x colour texture, 1) s, f90 = s.
void material_brdf(out float metallic, out float roughness, out vec3 f0, out float f90) {
  metallic = 0.0;
  roughness = 1.0;
  f0 = vec3(0.0);
  f90 = 0.0;
  if (u_lambertian) return;
  vec4 mr = u_has_mr_texture ? texture(u_mr_texture, material_uv(u_mr_map, u_mr_set)) : vec4(1.0);
  metallic = clamp(u_metallic * mr.b, 0.0, 1.0);
  roughness = clamp(u_roughness * mr.g, 0.0, 1.0);
  float s = u_specular;
  if (u_has_specular_texture)
    s *= texture(u_specular_texture, material_uv(u_specular_map, u_specular_set)).a;
  s = clamp(s, 0.0, 1.0);
  vec3 colour = vec3(1.0);
  if (u_has_specular_color_texture)
    colour = texture(u_specular_color_texture,
                     material_uv(u_specular_color_map, u_specular_color_set)).rgb;
  f0 = min(u_f0 * colour, vec3(1.0)) * s;
  f90 = s;
}
#endif
#ifdef IRAD_ALPHA
uniform int u_alpha_mode;     // 0 opaque, 1 mask, 2 blend
uniform float u_alpha_cutoff;
uniform float u_base_alpha;
float material_coverage() {
  float a = u_base_alpha;
  if (u_has_base_texture) a *= material_base_texel().a;
#ifdef IRAD_COLOR
  a *= v_color.a;
#endif
  return a;
}
uint alpha_hash(uint x) { // a 32-bit integer mix (lowbias32)
  x ^= x >> 16; x *= 0x7feb352du; x ^= x >> 15; x *= 0x846ca68bu; x ^= x >> 16;
  return x;
}
uint hash3(uvec3 b, uint h) { return alpha_hash(b.x ^ alpha_hash(b.y ^ alpha_hash(b.z ^ h))); }
// Camera passes: the fragment's world point (its float bits without the 10 lowest mantissa bits)
// and the primitive.
uint camera_alpha_key() {
  return hash3(floatBitsToUint(v_position) >> 10u, alpha_hash(uint(gl_PrimitiveID)));
}
// Shadow passes: the shadow texel, the primitive and the VPL (the bits of its position `vpl`).
uint shadow_alpha_key(vec3 vpl) {
  uvec3 t = uvec3(uvec2(gl_FragCoord.xy), uint(gl_PrimitiveID));
  return hash3(t, hash3(floatBitsToUint(vpl), 0u));
}
bool material_absent(uint key) {
  if (u_alpha_mode == 0) return false;
  float a = material_coverage();
  if (u_alpha_mode == 1) return a < u_alpha_cutoff;
  return !(float(key >> 8) * (1.0 / 16777216.0) < a);
}
#endif
)";

constexpr const char* kExtraNames[MaterialUniforms::kExtraTextures] = {"mr", "specular",
                                                                       "specular_color", "normal"};
constexpr GLint kExtraUnits[MaterialUniforms::kExtraTextures] = {
    metallic_roughness_unit, specular_unit, specular_color_unit, normal_unit};

GLint alpha_mode_value(AlphaMode mode) {
  return mode == AlphaMode::Mask ? 1 : mode == AlphaMode::Blend ? 2 : 0;
}

void bind_texture(const GladGLContext& api, const GpuScene& gpu, int texture, GLint has,
                  GLint unit) {
  api.Uniform1i(has, texture >= 0 ? 1 : 0);
  if (texture < 0 || has < 0) return;
  api.ActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(unit));
  api.BindTexture(GL_TEXTURE_2D, gpu.texture(texture));
}

} // namespace

MaterialFeatures MaterialFeatures::of(const Scene& scene) {
  MaterialFeatures f;
  f.uv1 = !scene.uvs1.empty();
  f.colors = !scene.colors.empty();
  for (const Material& m : scene.materials) f.alpha = f.alpha || m.alpha_mode != AlphaMode::Opaque;
  f.mirrors = scene.has_specular();
  f.glossy = !scene.all_lambertian();
  f.normal_maps = !scene.tangents.empty();
  return f;
}

std::string material_source(const std::string& source, const MaterialFeatures& features) {
  std::string s = source;
  const std::size_t line = s.find('\n');
  if (s.rfind("#version", 0) != 0 || line == std::string::npos)
    throw std::logic_error("material_source: the source does not start with #version");
  std::string defines;
  if (features.uv1) defines += "#define IRAD_UV1 1\n";
  if (features.colors) defines += "#define IRAD_COLOR 1\n";
  if (features.alpha) defines += "#define IRAD_ALPHA 1\n";
  if (features.mirrors) defines += "#define IRAD_MIRRORS 1\n";
  if (features.glossy) defines += "#define IRAD_GLOSSY 1\n";
  if (features.normal_maps) defines += "#define IRAD_NORMAL_MAP 1\n";
  s.insert(line + 1, defines);
  insert_glsl(s, kVertexMarker, kVertexGlsl);
  insert_glsl(s, kFragmentMarker, kFragmentGlsl);
  return s;
}

MaterialUniforms::MaterialUniforms(const ShaderProgram& program) {
  const auto at = [&](const char* name) { return program.optional_uniform(name); };
  base_color_ = at("u_base_color");
  has_base_texture_ = at("u_has_base_texture");
  base_map_ = at("u_base_map");
  base_set_ = at("u_base_set");
  emission_ = at("u_emission");
  has_emissive_texture_ = at("u_has_emissive_texture");
  emissive_map_ = at("u_emissive_map");
  emissive_set_ = at("u_emissive_set");
  alpha_mode_ = at("u_alpha_mode");
  alpha_cutoff_ = at("u_alpha_cutoff");
  base_alpha_ = at("u_base_alpha");
  lambertian_ = at("u_lambertian");
  metallic_ = at("u_metallic");
  roughness_ = at("u_roughness");
  f0_ = at("u_f0");
  specular_ = at("u_specular");
  for (int k = 0; k < kExtraTextures; ++k) {
    const std::string name = kExtraNames[k];
    extra_[k] = {at(("u_has_" + name + "_texture").c_str()), at(("u_" + name + "_map").c_str()),
                 at(("u_" + name + "_set").c_str())};
  }
  normal_scale_ = at("u_normal_scale");
  program.use(); // samplers of different types may not share a unit: fix them once
  program.set_sampler("u_base_texture", material_unit);
  program.set_sampler("u_emissive_texture", emissive_unit);
  for (int k = 0; k < kExtraTextures; ++k)
    program.set_sampler(("u_" + std::string(kExtraNames[k]) + "_texture").c_str(), kExtraUnits[k]);
  program.set_sampler("u_albedo_table", albedo_table_unit);
}

void MaterialUniforms::bind_map(const GladGLContext& api, GLint matrix, GLint set,
                                const TexCoordMap& map) const {
  api.UniformMatrix3fv(matrix, 1, GL_FALSE, glm::value_ptr(map.matrix));
  api.Uniform1i(set, map.texcoord);
}

void MaterialUniforms::bind_alpha(const GladGLContext& api, const GpuScene& gpu,
                                  const Material& m) const {
  if (alpha_mode_ < 0) return;
  api.Uniform1i(alpha_mode_, alpha_mode_value(m.alpha_mode));
  api.Uniform1f(alpha_cutoff_, m.alpha_cutoff);
  api.Uniform1f(base_alpha_, m.base_alpha);
  bind_texture(api, gpu, m.base_color_texture, has_base_texture_, material_unit);
  bind_map(api, base_map_, base_set_, m.base_color_map);
}

void MaterialUniforms::bind_base(const GladGLContext& api, const GpuScene& gpu, const Material& m,
                                 const glm::vec3& rho) const {
  api.Uniform3fv(base_color_, 1, glm::value_ptr(rho));
  bind_texture(api, gpu, m.base_color_texture, has_base_texture_, material_unit);
  bind_map(api, base_map_, base_set_, m.base_color_map);
  bind_alpha(api, gpu, m);
  bind_brdf(api, gpu, m);
}

void MaterialUniforms::bind_brdf(const GladGLContext& api, const GpuScene& gpu,
                                 const Material& m) const {
  const Scene& scene = gpu.scene();
  const int textures[kExtraTextures] = {m.metallic_roughness_texture, m.specular_texture,
                                        m.specular_color_texture, m.normal_texture};
  const TexCoordMap* maps[kExtraTextures] = {&m.metallic_roughness_map, &m.specular_map,
                                             &m.specular_color_map, &m.normal_map};
  const bool lambertian = MaterialUniforms::lambertian(m);
  for (int k = 0; k < kExtraTextures; ++k) {
    if (extra_[k].has < 0) continue;
    // As the CPU (texture_at): a texture without its texture coordinates is not read.
    const bool read = (k == 3 || !lambertian) && has_texcoords(scene, *maps[k]);
    bind_texture(api, gpu, read ? textures[k] : -1, extra_[k].has, kExtraUnits[k]);
    bind_map(api, extra_[k].map, extra_[k].set, *maps[k]);
  }
  if (normal_scale_ >= 0) api.Uniform1f(normal_scale_, m.normal_scale);
  if (lambertian_ < 0) return;
  api.Uniform1i(lambertian_, lambertian ? 1 : 0);
  api.Uniform1f(metallic_, m.metallic);
  api.Uniform1f(roughness_, m.roughness);
  const float r = (m.ior - 1.0f) / (m.ior + 1.0f);
  const glm::vec3 f0 = r * r * m.specular_color;
  api.Uniform3fv(f0_, 1, glm::value_ptr(f0));
  api.Uniform1f(specular_, m.specular_factor);
  api.ActiveTexture(GL_TEXTURE0 + albedo_table_unit);
  api.BindTexture(GL_TEXTURE_2D, gpu.albedo_table());
}

void MaterialUniforms::bind_emission(const GladGLContext& api, const GpuScene& gpu,
                                     const Material& m) const {
  api.Uniform3fv(emission_, 1, glm::value_ptr(m.emission));
  bind_texture(api, gpu, m.emissive_texture, has_emissive_texture_, emissive_unit);
  bind_map(api, emissive_map_, emissive_set_, m.emissive_map);
  bind_alpha(api, gpu, m);
}

} // namespace irad::gl
