#include "raster/context/shader_program.h"

#include "core/util/error.h"

#include <algorithm>
#include <vector>

namespace irad::gl {

namespace {

std::string one_line(std::string s) {
  std::replace(s.begin(), s.end(), '\n', ' ');
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

// The info log of a shader or program (GetShaderiv/GetShaderInfoLog or the program pair).
template <typename GetIv, typename GetLog>
std::string info_log(GLuint name, GetIv get_iv, GetLog get_log) {
  GLint length = 0;
  get_iv(name, GL_INFO_LOG_LENGTH, &length);
  std::vector<char> log(static_cast<std::size_t>(std::max(length, 1)), '\0');
  get_log(name, static_cast<GLsizei>(log.size()), nullptr, log.data());
  return one_line(log.data());
}

Shader compile(const GladGLContext& api, GLenum stage, const std::string& source,
               const std::string& name) {
  Shader shader(api, api.CreateShader(stage));
  const char* text = source.c_str();
  api.ShaderSource(shader.get(), 1, &text, nullptr);
  api.CompileShader(shader.get());
  GLint ok = GL_FALSE;
  api.GetShaderiv(shader.get(), GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    const char* kind = stage == GL_VERTEX_SHADER ? "vertex" : "fragment";
    throw Error("", "shader " + name,
                std::string(kind) +
                    " stage: " + info_log(shader.get(), api.GetShaderiv, api.GetShaderInfoLog));
  }
  return shader;
}

} // namespace

void insert_glsl(std::string& source, const std::string& marker, const char* text) {
  const std::size_t at = source.find(marker);
  if (at != std::string::npos) source.replace(at, marker.size(), text);
}

void check_framebuffer(const GladGLContext& api, const char* what) {
  const GLenum status = api.CheckFramebufferStatus(GL_DRAW_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE)
    throw Error("", what, "framebuffer incomplete (status 0x" + std::to_string(status) + ")");
}

ShaderProgram::ShaderProgram(const GladGLContext& api, const std::string& name,
                             const std::string& vertex, const std::string& fragment)
    : api_(&api), name_(name), program_(api, api.CreateProgram()) {
  const Shader vs = compile(api, GL_VERTEX_SHADER, vertex, name);
  const Shader fs = compile(api, GL_FRAGMENT_SHADER, fragment, name);
  api.AttachShader(program_.get(), vs.get());
  api.AttachShader(program_.get(), fs.get());
  api.LinkProgram(program_.get());
  GLint ok = GL_FALSE;
  api.GetProgramiv(program_.get(), GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE)
    throw Error("", "shader " + name,
                "link: " + info_log(program_.get(), api.GetProgramiv, api.GetProgramInfoLog));
  api.DetachShader(program_.get(), vs.get());
  api.DetachShader(program_.get(), fs.get());
}

GLint ShaderProgram::uniform(const char* uniform_name) const {
  const GLint location = api_->GetUniformLocation(program_.get(), uniform_name);
  if (location < 0) throw Error("", "shader " + name_, std::string("no uniform ") + uniform_name);
  return location;
}

GLint ShaderProgram::optional_uniform(const char* uniform_name) const {
  return api_->GetUniformLocation(program_.get(), uniform_name);
}

void ShaderProgram::set_sampler(const char* uniform_name, GLint unit) const {
  const GLint location = optional_uniform(uniform_name);
  if (location >= 0) api_->Uniform1i(location, unit);
}

} // namespace irad::gl
