// The GL layer's failure paths: every compile, link and framebuffer problem is an irad::Error
// on one line, never a black image.
#include "core/error.h"
#include "raster/gl_context.h"
#include "raster/shader_program.h"
#include "raster/target.h"

#include <gtest/gtest.h>

namespace irad {
namespace {

const char* good_vertex = "#version 330 core\nvoid main() { gl_Position = vec4(0.0); }\n";

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(Gl, OsMesaCoreContext) {
  const auto context = gl::create_osmesa_context();
  EXPECT_EQ(context->backend(), "osmesa");
  EXPECT_NE(context->renderer().find("Core Profile"), std::string::npos) << context->renderer();
}

TEST(Gl, CompileErrorIsOneLineNamingTheShader) {
  const auto context = gl::create_osmesa_context();
  const std::string m = message_of([&] {
    gl::ShaderProgram(context->api(), "broken", good_vertex,
                      "#version 330 core\nout vec4 c;\nvoid main() { c = undefined_thing; }\n");
  });
  EXPECT_NE(m.find("shader broken"), std::string::npos) << m;
  EXPECT_NE(m.find("fragment"), std::string::npos) << m;
  EXPECT_EQ(m.find('\n'), std::string::npos) << m;
}

TEST(Gl, LinkErrorIsReported) {
  const auto context = gl::create_osmesa_context();
  // The stages disagree on the type of a varying.
  const std::string m = message_of([&] {
    gl::ShaderProgram(context->api(), "unlinked",
                      "#version 330 core\nout vec2 v;\n"
                      "void main() { v = vec2(1.0); gl_Position = vec4(0.0); }\n",
                      "#version 330 core\nin vec3 v;\nout vec4 c;\n"
                      "void main() { c = vec4(v, 1.0); }\n");
  });
  EXPECT_NE(m.find("shader unlinked"), std::string::npos) << m;
  EXPECT_EQ(m.find('\n'), std::string::npos) << m;
}

TEST(Gl, MissingUniformIsAnError) {
  const auto context = gl::create_osmesa_context();
  const gl::ShaderProgram p(context->api(), "plain", good_vertex,
                            "#version 330 core\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n");
  EXPECT_THROW(p.uniform("u_not_there"), Error);
}

TEST(Gl, TargetBeyondTheImplementationLimitIsRefused) {
  const auto context = gl::create_osmesa_context();
  const std::string m = message_of([&] { gl::Target(context->api(), 1 << 20, 4); });
  EXPECT_NE(m.find("--size"), std::string::npos) << m;
  const gl::Target ok(context->api(), 8, 4);
  const Image image = ok.read();
  EXPECT_EQ(image.width(), 8);
  EXPECT_EQ(image.height(), 4);
}

} // namespace
} // namespace irad
