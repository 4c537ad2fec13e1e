#include "raster/glsl/mirror_shaders.h"

#include <stdexcept>

namespace irad::gl::shaders {

std::string mirror_vpl_fragment(const char* vpl_fragment) {
  std::string source(vpl_fragment);
  const std::string main = "void main() {";
  const std::size_t at = source.find(main);
  if (at == std::string::npos) throw std::logic_error("vpl_fragment has no 'void main() {'");
  source.insert(at + main.size(), "\n  if (!through_mirror(v_position)) discard;");
  source.insert(at, std::string(mirror_clip_uniforms) + mirror_pyramid_glsl + mirror_clip_call);
  return source;
}

} // namespace irad::gl::shaders
