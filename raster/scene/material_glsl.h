#pragma once
// The GLSL that every program reading a material shares: texture coordinates through the
// material's TexCoordMap, COLOR_0, and the alpha coverage rule (core/scene/scene.h coverage_at).
// A program's source marks where the shared text goes with two lines:
//   "#pragma irad_material_vertex"    (vertex stage: the attributes, varyings and
//                                      copy_material_attributes())
//   "#pragma irad_material_fragment"  (fragment stage: the uniforms, material_albedo(),
//                                      material_emission(), material_normal(), with alpha
//                                      material_absent(), with IRAD_GLOSSY material_brdf())
// material_source() replaces them and defines, after the version line, only the features the
// scene has: IRAD_UV1 (TEXCOORD_1), IRAD_COLOR (COLOR_0), IRAD_ALPHA (a Mask or Blend material),
// IRAD_MIRRORS, IRAD_GLOSSY (a material that is not Lambertian: metallic, roughness, f0 and f90
// from factors and textures) and IRAD_NORMAL_MAP (tangents: material_normal() reads the map).
// A scene with none of them compiles none of their code (the uv transform is one mat3 product,
// exact for the identity), so its images are bit-identical to those of shaders without them.
#include "core/scene/scene.h"
#include "raster/context/shader_program.h"
#include "raster/scene/gpu_scene.h"
#include "raster/scene/material_features.h"

#include <string>

namespace irad::gl {

// `source` with the defines of `features` after its first line and the markers above replaced.
std::string material_source(const std::string& source, const MaterialFeatures& features);

// The locations of the shared material uniforms in one program (-1 where the program does not
// use one: GL ignores uniform calls at -1), and their values for one material.
class MaterialUniforms {
public:
  explicit MaterialUniforms(const ShaderProgram& program);
  // Base colour rho (the caller zeroes it for mirrors), its texture on material_unit and map,
  // and the alpha mode, cutoff and base alpha.
  void bind_base(const GladGLContext& api, const GpuScene& gpu, const Material& m,
                 const glm::vec3& rho) const;
  // Emission, its texture on material_unit and map (and the alpha uniforms of m).
  void bind_emission(const GladGLContext& api, const GpuScene& gpu, const Material& m) const;
  // Only the alpha uniforms and the base texture that coverage reads (shadow and depth passes).
  void bind_alpha(const GladGLContext& api, const GpuScene& gpu, const Material& m) const;

  // The textures beside the base colour's: metallic-roughness, specular, specular colour, normal.
  static constexpr int kExtraTextures = 4;
  // Whether the programs take m as Lambertian (m = f0 = f90 = 0): Material::lambertian() or a
  // mirror (whose diffuse the caller zeroes).
  static bool lambertian(const Material& m) { return m.lambertian() || m.specular; }

private:
  // The BRDF's uniforms and textures (IRAD_GLOSSY) and the normal map (IRAD_NORMAL_MAP); part of
  // bind_base. A mirror or a Lambertian material sets u_lambertian and reads none of them.
  void bind_brdf(const GladGLContext& api, const GpuScene& gpu, const Material& m) const;
  void bind_map(const GladGLContext& api, GLint matrix, GLint set, const TexCoordMap& map) const;
  GLint base_color_, has_base_texture_, base_map_, base_set_;
  GLint emission_, has_emissive_texture_, emissive_map_, emissive_set_;
  GLint alpha_mode_, alpha_cutoff_, base_alpha_;
  GLint lambertian_, metallic_, roughness_, f0_, specular_, normal_scale_;
  struct TextureUniforms {
    GLint has = -1, map = -1, set = -1;
  };
  TextureUniforms extra_[kExtraTextures];
};

} // namespace irad::gl
