#pragma once
// A linked GLSL program. Compilation and link failures throw irad::Error with the driver's log
// (folded onto one line). Uniform locations are looked up once, at construction, by the caller.
#include "raster/context/gl_objects.h"

#include <string>

namespace irad::gl {

// How shaders share GLSL: `source` with its first line `marker` (e.g. "#pragma
// irad_material_fragment\n") replaced by `text`; unchanged without one.
void insert_glsl(std::string& source, const std::string& marker, const char* text);

class ShaderProgram {
public:
  ShaderProgram(const GladGLContext& api, const std::string& name, const std::string& vertex,
                const std::string& fragment);
  GLuint get() const { return program_.get(); }
  // Location of a uniform that must exist (throws otherwise: a typo is a bug, not a no-op).
  GLint uniform(const char* uniform_name) const;
  // Location of a uniform the program may have optimised away (-1 then: GL ignores calls there).
  GLint optional_uniform(const char* uniform_name) const;
  // Sets sampler `uniform_name` (if the program uses it) to texture unit `unit`; the program must
  // be in use.
  void set_sampler(const char* uniform_name, GLint unit) const;
  void use() const { api_->UseProgram(program_.get()); }

private:
  const GladGLContext* api_;
  std::string name_;
  Program program_;
};

} // namespace irad::gl
