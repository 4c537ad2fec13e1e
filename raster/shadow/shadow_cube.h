#pragma once
// Omnidirectional shadow map of one VPL: a cube of RGBA32F texels, the distance |p - y| to the
// nearest surface and its gradient per texel (raster/glsl/cube_glsl.h),
// rendered face by face into one framebuffer. A surface VPL lights only its hemisphere, so its
// cube is turned to put the normal at the centre of the +z face and the -z face is skipped.
// A mirrored VPL (core/scene/mirrors.h) gets the cube of its unfolded paths
// (raster/glsl/mirror_shaders.h).
#include "core/lights/vpl.h"
#include "core/scene/bounds.h"
#include "raster/context/shader_program.h"
#include "raster/scene/gpu_scene.h"
#include "raster/scene/material_glsl.h"

#include <array>
#include <functional>
#include <glm/glm.hpp>
#include <memory>

namespace irad::gl {

// GL's cube face order: +x, -x, +y, -y, +z, -z.
inline constexpr int kNegativeZFace = 5;

// The six face view-projections of a VPL's cube (what ShadowCube renders, also used by the
// batched shadow atlas, raster/shadow/shadow_atlas.h): frame is the rotation world -> cube frame;
// hemisphere (surface VPLs) means the -z face is never looked up and the side faces only on the
// half front_half() gives.
struct CubeFaces {
  glm::mat3 frame{1.0f};
  std::array<glm::mat4, 6> view_projection;
  float far = 1.0f; // the far plane
  bool hemisphere = false;
};
// far: the largest distance to be stored (far_from for an ordinary VPL), widened by 1 %.
CubeFaces cube_faces(const Vpl& vpl, const Bounds& bounds, float far);
// The distance from `position` to the farthest corner of `bounds`.
float far_from(const Bounds& bounds, const glm::vec3& position);
// The window rectangle (x, y, w, h) of side face f (+x, -x, +y, -y) of a resolution r face that
// sees local z >= 0, with one texel of margin.
glm::ivec4 front_half(int f, int r);

class ShadowCube {
public:
  // features: the scene's (raster/scene/material_features.h); with alpha, absent fragments cast no
  // shadow.
  ShadowCube(const GladGLContext& api, int resolution, const Bounds& bounds,
             const MaterialFeatures& features);

  // Renders the cube for `vpl` (changes the bound framebuffer, viewport and program) and returns
  // the rotation world -> cube frame to use for lookups.
  glm::mat3 render(const Vpl& vpl, const GpuScene& scene) {
    return render_into(vpl, scene, cube_.get());
  }
  // The same into `cube`, a cube map from make_cube(resolution()) (shadow maps kept per VPL).
  glm::mat3 render_into(const Vpl& vpl, const GpuScene& scene, GLuint cube);
  // An RGBA32F cube map of resolution^2 faces with the lookup state the shading pass expects.
  static Texture make_cube(const GladGLContext& api, int resolution);

  GLuint texture() const { return cube_.get(); }
  int resolution() const { return resolution_; }
  // Angular size of one texel at the centre of a face (radians, ~2 / resolution).
  float texel_angle() const { return 2.0f / static_cast<float>(resolution_); }

private:
  // The program of mirrored VPLs' cubes (raster/glsl/mirror_shaders.h), made on first use.
  struct MirrorProgram {
    MirrorProgram(const GladGLContext& api, const MaterialFeatures& features);
    ShaderProgram program;
    MaterialUniforms material;
    GLint face_view_projection, vpl_position, reflect, clip_plane;
  };
  float far_from(const glm::vec3& position) const;
  glm::mat3 render_mirrored(const Vpl& vpl, const GpuScene& scene);
  // Clears and draws the faces the VPL needs (draw(face view-projection) for each).
  glm::mat3 render_faces(const Vpl& vpl, float far,
                         const std::function<void(const glm::mat4&)>& draw);

  std::unique_ptr<MirrorProgram> mirror_;
  const GladGLContext* api_;
  int resolution_;
  Bounds bounds_;
  MaterialFeatures features_;
  ShaderProgram program_;
  MaterialUniforms material_;
  GLint u_face_view_projection_;
  GLint u_vpl_position_;
  Texture cube_;
  Renderbuffer depth_;
  std::array<Framebuffer, 6> fbos_; // one per face, built once: no re-attachment per VPL
  GLuint attached_ = 0;             // the cube whose faces the framebuffers hold
};

} // namespace irad::gl
