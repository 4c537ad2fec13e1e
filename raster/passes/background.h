#pragma once
// The background pass: where a camera ray sees no surface, the pixel shows the distant
// environment's L(w) (core/environment/environment.h, when the scene has one and it is `visible`)
// plus the disks of the visible suns (directional lights with angular_radius > 0,
// core/scene/scene.h), w the ray through the pixel centre (core/camera/view.h pixel_ray). Drawn
// after everything else as a triangle at depth 1 with GL_LEQUAL and depth writes off, over the
// depth buffer of the visible surface, so it adds to the pixels that no surface covers and to no
// other. Which of the two shows: the map when environment && environment->visible && it is not
// black; the suns unless the scene has an environment with visible == false (the flag,
// --env-visible, says what camera rays that miss see: all of it or nothing), so a sun without an
// environment shows its disk on black. A scene that shows neither gets no Background (make()
// returns null): no program, no texture, no pass.
#include "core/camera/view.h"
#include "core/scene/scene.h"
#include "raster/context/shader_program.h"

#include <glm/glm.hpp>
#include <memory>
#include <vector>

namespace irad::gl {

// Suns shown at most; further ones are left out of the background (never of the lighting).
inline constexpr int kMaxVisibleSuns = 16;

class Background {
public:
  // The pass for `scene`, or nullptr when it shows nothing past the geometry. Throws irad::Error
  // naming the map when it exceeds GL_MAX_TEXTURE_SIZE or GL cannot hold it.
  static std::unique_ptr<Background> make(const GladGLContext& api, const Scene& scene);
  Background(const GladGLContext& api, const Scene& scene);

  // Adds weight * (L_env(w) + suns(w)) into the bound framebuffer wherever its depth is 1, w the
  // ray of view's pixel centre seen through view_projection (view.projection * view.view, or a
  // jittered projection times view.view: raster/image/pixel_jitter.h).
  void draw(const View& view, const glm::mat4& view_projection, float weight = 1.0f) const;

private:
  void upload_map(const Environment& environment);
  void set_suns(const Scene& scene) const;

  const GladGLContext* api_;
  bool shows_map_;
  int suns_;
  int bands_; // textures the map is split into (raster/glsl/environment_glsl.h)
  int band_rows_;
  ShaderProgram program_;
  std::vector<Texture> map_;
  VertexArray empty_vao_;
  GLint inverse_vp_, size_, eye_, forward_, orthographic_;
};

// Whether the background of `scene` shows its environment map, and the suns it shows.
bool shows_environment_map(const Scene& scene);
std::vector<const PunctualLight*> visible_suns(const Scene& scene);

} // namespace irad::gl
