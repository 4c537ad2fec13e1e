#include "raster/passes/background.h"

#include "core/util/error.h"
#include "raster/glsl/environment_glsl.h"
#include "raster/glsl/shaders.h"
#include "raster/passes/vpl_shader.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <glm/gtc/type_ptr.hpp>

namespace irad::gl {

namespace {

constexpr GLint environment_unit = 7; // and the next bands - 1 units

// Bands of at most 512 MiB of RGB32F (llvmpipe's limit is 1 GiB per texture), at most 4: the
// largest map, 16384 x 8192, takes 3.
int bands_for(const Scene& scene) {
  if (!shows_environment_map(scene)) return 0;
  const Image& map = scene.environment->map();
  const std::size_t bytes = std::size_t(map.width()) * std::size_t(map.height()) * 12u;
  const std::size_t band = std::size_t{512} << 20;
  return static_cast<int>(std::clamp<std::size_t>((bytes + band - 1) / band, 1, 4));
}

std::string fragment_source(int bands, int suns) {
  std::string s = "#version 330 core\n";
  if (bands > 0)
    s += fmt::format("#define IRAD_ENVIRONMENT\n#define IRAD_ENVIRONMENT_BANDS {}\n", bands);
  s += fmt::format("#define IRAD_SUNS {}\n", suns);
  if (bands > 0) s += shaders::environment_lookup;
  if (suns > 0) s += shaders::sun_disks;
  return s + shaders::background_fragment;
}

} // namespace

bool shows_environment_map(const Scene& scene) {
  return scene.environment && scene.environment->visible && !scene.environment->black();
}

std::vector<const PunctualLight*> visible_suns(const Scene& scene) {
  std::vector<const PunctualLight*> suns;
  if (scene.environment && !scene.environment->visible) return suns;
  for (const PunctualLight& l : scene.lights)
    if (l.kind == PunctualLight::Kind::Directional && l.angular_radius > 0.0f &&
        static_cast<int>(suns.size()) < kMaxVisibleSuns)
      suns.push_back(&l);
  return suns;
}

std::unique_ptr<Background> Background::make(const GladGLContext& api, const Scene& scene) {
  if (!shows_environment_map(scene) && visible_suns(scene).empty()) return nullptr;
  return std::make_unique<Background>(api, scene);
}

Background::Background(const GladGLContext& api, const Scene& scene)
    : api_(&api), shows_map_(shows_environment_map(scene)),
      suns_(static_cast<int>(visible_suns(scene).size())), bands_(bands_for(scene)), band_rows_(0),
      program_(api, "background", shaders::fullscreen_vertex, fragment_source(bands_, suns_)),
      empty_vao_(make_vertex_array(api)),
      inverse_vp_(program_.optional_uniform("u_inverse_view_projection")),
      size_(program_.optional_uniform("u_size")), eye_(program_.optional_uniform("u_eye")),
      forward_(program_.optional_uniform("u_forward")),
      orthographic_(program_.uniform("u_orthographic")) {
  program_.use();
  // At the far plane: GL_LEQUAL then keeps exactly the pixels where no surface was drawn.
  api.Uniform1f(program_.uniform("u_depth"), 1.0f);
  if (shows_map_) upload_map(*scene.environment);
  if (suns_ > 0) set_suns(scene);
}

// The map as stored (RGB of its RGBA texels, strength applied in the shader), row 0 first: the
// zenith row, which texelFetch's row 0 then is.
void Background::upload_map(const Environment& environment) {
  const GladGLContext& api = *api_;
  const Image& map = environment.map();
  GLint max_size = 0;
  api.GetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
  if (map.width() > max_size || map.height() > max_size)
    throw Error(environment.source(), "environment map",
                fmt::format("{}x{} exceeds this OpenGL's largest texture ({}x{}): shown as the "
                            "background it must fit",
                            map.width(), map.height(), max_size, max_size));
  while (api.GetError() != GL_NO_ERROR) { // the error checked below is the upload's own
  }
  band_rows_ = (map.height() + bands_ - 1) / bands_;
  api.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
  std::vector<GLint> units;
  for (int b = 0; b < bands_; ++b) {
    const int first = b * band_rows_, rows = std::min(band_rows_, map.height() - first);
    map_.push_back(make_texture(api));
    api.ActiveTexture(GL_TEXTURE0 + environment_unit + b);
    api.BindTexture(GL_TEXTURE_2D, map_.back().get());
    api.TexImage2D(GL_TEXTURE_2D, 0, GL_RGB32F, map.width(), rows, 0, GL_RGBA, GL_FLOAT,
                   map.pixels().data() + std::size_t(first) * std::size_t(map.width()));
    // texelFetch ignores filtering; these make the texture complete without mipmaps.
    api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    units.push_back(environment_unit + b);
  }
  if (const GLenum e = api.GetError(); e != GL_NO_ERROR)
    throw Error(environment.source(), "environment map",
                fmt::format("OpenGL could not hold the {}x{} map as {} texture(s) (error 0x{:x})",
                            map.width(), map.height(), bands_, e));
  api.Uniform1iv(program_.uniform("u_environment[0]"), bands_, units.data());
  api.Uniform2i(program_.uniform("u_environment_size"), map.width(), map.height());
  api.Uniform1i(program_.uniform("u_environment_band_rows"), band_rows_);
  const float c = std::cos(environment.rotation()), s = std::sin(environment.rotation());
  api.Uniform2f(program_.uniform("u_environment_rotation"), c, s);
  api.Uniform1f(program_.uniform("u_environment_strength"), environment.strength());
  api.ActiveTexture(GL_TEXTURE0);
}

// Sun k: toward = -direction, cos r, and the disk's radiance E / (pi sin^2 r).
void Background::set_suns(const Scene& scene) const {
  const GladGLContext& api = *api_;
  std::vector<glm::vec3> toward, radiance;
  std::vector<float> cosines;
  for (const PunctualLight* l : visible_suns(scene)) {
    toward.push_back(-glm::normalize(l->direction));
    cosines.push_back(std::cos(l->angular_radius));
    radiance.push_back(sun_disk_radiance(*l)); // core/scene/scene.h, the CPU estimators' value
  }
  api.Uniform3fv(program_.uniform("u_sun_toward"), suns_, glm::value_ptr(toward.front()));
  api.Uniform1fv(program_.uniform("u_sun_cos"), suns_, cosines.data());
  api.Uniform3fv(program_.uniform("u_sun_radiance"), suns_, glm::value_ptr(radiance.front()));
}

void Background::draw(const View& view, const glm::mat4& view_projection, float weight) const {
  const GladGLContext& api = *api_;
  set_additive_state(api); // GL_LEQUAL, no depth writes, adding
  if (weight != 1.0f) {
    api.BlendColor(0.0f, 0.0f, 0.0f, weight);
    api.BlendFunc(GL_CONSTANT_ALPHA, GL_ONE);
  }
  program_.use();
  // The unjittered view-projection's inverse is the CPU's own (make_view), bit for bit.
  const glm::mat4 inverse = view_projection == view.projection * view.view
                                ? view.inverse_view_projection
                                : glm::inverse(view_projection);
  api.UniformMatrix4fv(inverse_vp_, 1, GL_FALSE, glm::value_ptr(inverse));
  api.Uniform2f(size_, static_cast<float>(view.width), static_cast<float>(view.height));
  api.Uniform3fv(eye_, 1, glm::value_ptr(view.eye));
  api.Uniform3fv(forward_, 1, glm::value_ptr(view.forward));
  api.Uniform1i(orthographic_, view.orthographic ? 1 : 0);
  for (int b = 0; b < bands_; ++b) {
    api.ActiveTexture(GL_TEXTURE0 + environment_unit + b);
    api.BindTexture(GL_TEXTURE_2D, map_[std::size_t(b)].get());
  }
  api.BindVertexArray(empty_vao_.get());
  api.DrawArrays(GL_TRIANGLES, 0, 3);
  api.BlendFunc(GL_ONE, GL_ONE);
  api.ActiveTexture(GL_TEXTURE0);
}

} // namespace irad::gl
