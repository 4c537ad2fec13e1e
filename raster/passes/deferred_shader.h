#pragma once
// The deferred shading of a batch of VPLs: the camera's G-buffer (raster/image/gbuffer.h) holds
// the one surface each pixel sees; a draw is an instanced full-screen triangle over the bound
// viewport (the image, or one interleaved set's tile), instance i adding w * C(x)
// (core/lights/vpl.h, the maths of raster/passes/vpl_shader.h) of the draw's VPL i, its shadow map
// looked up in a ShadowAtlas or an OrthoAtlas. The cost of a batch is pixels x VPLs, whatever the
// number of triangles, and a pixel is lit once even where two faces coincide (duplicated faces,
// back-to-back walls), which the forward passes light once per face that passes the depth test.
// In a scene with a material that is not Lambertian the light is f_r,x (from the G-buffer) times
// the glossy VPLs' lobes (AtlasVpl::lobe).
#include "core/lights/vpl.h"
#include "core/scene/mirrors.h"
#include "core/scene/scene.h"
#include "raster/context/shader_program.h"
#include "raster/image/gbuffer.h"
#include "raster/scene/gpu_scene.h"

#include <array>
#include <glm/glm.hpp>
#include <memory>
#include <vector>

namespace irad::gl {

// Where a draw's fragments read the G-buffer: tile pixel t of a viewport with lower-left corner
// `origin` stands for image pixel k t + offset; with a `list` (an RG32I texture,
// raster/image/edge_pixels.h) for the pixel its texel t - origin holds (none where x < 0).
struct TilePixels {
  glm::ivec2 origin{0};
  int k = 1;
  glm::ivec2 offset{0};
  GLuint list = 0;
  // The bound framebuffer's depth is a ReceiverMask of the draw's G-buffer
  // (raster/image/receiver_mask.h): a glossy scene's Lambertian and glossy pixels are drawn apart.
  bool receivers = false;
};

// The atlases a draw's VPLs look their shadow maps up in: cubes in raster/shadow/shadow_atlas.h's
// layout (blocks of resolution^2 faces), orthographic maps in raster/shadow/ortho_atlas.h's
// (tiles of ortho_resolution^2 texels; 0: none).
struct ShadowLookup {
  GLuint texture = 0;
  int resolution = 0;
  GLuint ortho_texture = 0;
  int ortho_resolution = 0;
  GLuint gradient = 0; // the distances' gradients, texel by texel as `texture`; 0: none
  // Visibility by rays instead (DeferredShader made with `rays`; raster/passes/ray_visibility.h):
  // a 2D array texture, layer r the uploaded VPL r's answers over the draw's tile pixels.
  GLuint visibility = 0;
};

// A VPL whose shadow map is in an atlas, with what the lookup needs and its interleaved set.
// A cube (any kind but Directional): frame (world -> cube frame), far plane and blocks (atlas
// texels of its first block, xy, and second, zw; ShadowAtlas::render's outputs). Directional:
// `lookup` (world -> (u, v over its tile, depth along d); OrthoAtlas::render's), its tile's first
// texel in blocks.xy, and the map's half width and texel width in world units.
struct AtlasVpl {
  const Vpl* vpl = nullptr;
  glm::mat3 frame{1.0f};
  float far = 1.0f;
  glm::ivec4 blocks{0};
  int set = 0;
  glm::mat4 lookup{1.0f};
  float half_width = 0.0f, texel = 0.0f;
  // A glossy VPL's lobe (VplSet::lobes[vpl->lobe]); nullptr: Lambertian.
  const VplLobe* lobe = nullptr;
};

class DeferredShader {
public:
  // Up to `batch` VPLs per upload.
  // planes: the occluder planes' lookup (raster/glsl/cube_glsl.h) compiled in; every draw's
  // ShadowLookup must then carry gradients. Without, gradients are not read. unsure: alpha adds
  // the light of the VPLs whose shadow lookup was unsure, unshadowed (cube_glsl.h
  // lookup_unsure; its luminance, without rho(x)); without, alpha adds 0.
  // A draw whose ShadowLookup has `visibility` reads it instead of any shadow map (a program
  // of its own, without planes or unsure light).
  DeferredShader(const GladGLContext& api, const Scene& scene, float clamp, int batch, bool planes,
                 bool unsure)
      : DeferredShader(api, scene, clamp, batch, planes, unsure,
                       scene.has_specular() ? find_mirrors(scene) : std::vector<MirrorPolygon>{}) {}

  // The largest batch (<= wanted) this GL's uniform blocks hold (glossy: a scene with a material
  // that is not Lambertian, whose records carry the VPLs' lobes).
  static int capacity(const GladGLContext& api, int wanted, bool glossy);

  // The batch's VPLs vpls[0..n) (n <= batch()).
  void upload(const AtlasVpl* vpls, int n);
  // Adds the uploaded VPLs first..first + count - 1 into the bound framebuffer and viewport
  // (apply_albedo false: irradiance / pi without rho(x), for the interleaved resolve). In a glossy
  // scene each run of Lambertian VPLs is drawn by a program without the lobes' code: a caller
  // that orders a draw's glossy VPLs together draws the others at a Lambertian VPL's cost.
  void draw(int first, int count, const TilePixels& pixels, const GBuffer& gbuffer,
            const ShadowLookup& shadow, bool apply_albedo) const;
  int batch() const { return batch_; }
  // Glossy scenes: receivers of roughness below r shade only their diffuse lobe from the VPLs a
  // ray can meet (RasterOptions::traced_roughness); 0 (the default): none.
  void set_traced_roughness(float r) { traced_roughness_ = r; }
  // Whether the atlases the next draws read hold occluder planes (the constructor's `planes`):
  // the shadow maps' programs are made again on their next use.
  void set_planes(bool planes);

private:
  // `mirrors`: the scene's mirror polygons (find_mirrors), their corners uploaded to a texture.
  DeferredShader(const GladGLContext& api, const Scene& scene, float clamp, int batch, bool planes,
                 bool unsure, const std::vector<MirrorPolygon>& mirrors);

  const GladGLContext* api_;
  float diagonal_, clamp_;
  int batch_;
  bool planes_;
  // The scene has a material that is not Lambertian: the VPLs' lobes and the receivers' BRDF
  // (raster/glsl/deferred_shaders.h, IRAD_GLOSSY).
  bool glossy_;
  // Per mirror polygon (core/scene/mirrors.h) the triangles its pyramid test reads (<=
  // max_triangles).
  std::vector<int> mirror_triangles_;
  // A compiled variant of the shaders and its uniforms' locations: in a glossy scene with the
  // receivers' BRDF or without it (Lambertian pixels alone), with the VPLs' lobes or without them
  // (Lambertian VPLs alone).
  struct Program {
    Program(const GladGLContext& api, int batch, bool planes, bool unsure, bool mirrors,
            bool glossy, bool receivers, bool lobes, bool rays);
    ShaderProgram program;
    GLint first, tile_origin, pixel, size, shadow_res, shadow_half, bias_texel, ortho_res,
        apply_albedo, listed, eye, traced, depth;
  };
  // The variant, compiled at its first use.
  const Program& program(bool receivers, bool lobes, bool rays) const;
  // Whether a draw over `pixels` goes through the receiver mask: Lambertian and glossy pixels
  // apart.
  bool masked(const TilePixels& pixels) const { return glossy_ && pixels.receivers; }
  // Sets the uniforms and textures of every draw, and draws instances first..first + count - 1
  // at window depth `depth`: where masked(pixels), only over the mask's pixels that hold it.
  void draw_run(const Program& p, int first, int count, const TilePixels& pixels,
                const GBuffer& gbuffer, const ShadowLookup& shadow, bool apply_albedo,
                float depth) const;

  bool unsure_, mirrors_;
  // programs_[receivers + 2 lobes + 4 rays] (a Lambertian scene uses only programs_[0] and [4]).
  mutable std::array<std::unique_ptr<Program>, 8> programs_;
  // Per uploaded VPL: whether it has a lobe (AtlasVpl::lobe).
  std::vector<bool> lobed_;
  float traced_roughness_ = 0.0f;
  Texture mirror_corners_; // with mirrors: their corners (raster/glsl/deferred_shaders.h)
  Texture albedo_table_;   // glossy: raster/scene/gpu_scene.h albedo_table_texture
  Buffer vpl_block_;
  VertexArray empty_vao_;
  std::vector<float> vpl_data_;
};

} // namespace irad::gl
