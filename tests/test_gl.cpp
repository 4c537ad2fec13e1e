// The GL layer's failure paths: every compile, link and framebuffer problem is an irad::Error
// on one line, never a black image.
#include "core/camera/view.h"
#include "core/gltf/loader.h"
#include "core/image/image_metrics.h"
#include "core/util/error.h"
#include "raster/context/gl_context.h"
#include "raster/context/shader_program.h"
#include "raster/image/target.h"
#include "raster/raster_renderer.h"
#include "tests/test_paths.h"
#include "walk/vpls/quasi_random_walk.h"

#include <gtest/gtest.h>

namespace irad {
namespace IRAD_UNITY_ID {

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

TEST(Gl, EglSurfacelessCoreContext) {
  const auto context = gl::create_egl_context(-1);
  EXPECT_EQ(context->backend().rfind("egl", 0), 0u) << context->backend();
  EXPECT_NE(context->renderer().find("Core Profile"), std::string::npos) << context->renderer();
  EXPECT_THROW(gl::create_egl_context(1000), Error);
}

// OSMesa and EGL drive the same Mesa rasterizer here: the images must agree, for the Lambertian
// box and the glossy one (the G-buffer's material channels, the glossy VPLs' lobes). Measured on
// llvmpipe: bit-identical (RMSE 0); on different drivers expect rounding-level differences.
TEST(Gl, OsMesaAndEglGiveTheSameImage) {
  Log log([](const std::string&) {});
  for (const char* file : {"/data/cornell_box.gltf", "/data/cornell_glossy.gltf"}) {
    const Scene s = load_gltf(std::string(IRAD_SOURCE_DIR) + file, log);
    const RayScene rays(s);
    const VplSet vpls = quasi_random_walk(s, rays, {32, 64}, log);
    const View view = make_view(s.cameras.at(0), s.bounds, 64, 64);
    RasterOptions options;
    options.backend = GlBackend::OsMesa;
    const Image a = RasterRenderer(s, options).render(view, vpls);
    options.backend = GlBackend::Egl;
    RasterRenderer egl(s, options);
    EXPECT_EQ(egl.description().rfind("egl", 0), 0u) << egl.description();
    const Image b = egl.render(view, vpls);
    const ImageMetrics m = compare_images(a, b);
    EXPECT_LT(m.max_abs_error, 1e-6) << file;
  }
}

// KHR_debug messages reach the sink the renderer gives (the log), one line each.
TEST(Gl, DebugMessagesAreRouted) {
  const auto context = gl::create_osmesa_context();
  std::vector<std::string> messages;
  context->route_debug_messages([&](const std::string& m) { messages.push_back(m); });
  if (!context->api().KHR_debug) GTEST_SKIP() << "no KHR_debug on " << context->renderer();
  context->api().BindTexture(GL_TEXTURE_2D, 123456u); // not a texture name: an error
  ASSERT_FALSE(messages.empty());
  EXPECT_NE(messages.front().find("OpenGL error"), std::string::npos) << messages.front();
  EXPECT_EQ(messages.front().find('\n'), std::string::npos);
  EXPECT_THROW(context->check("after a bad bind"), Error);
}

// Errors reach the sink every time; any other kind of message (source, type, id) once, as a
// driver's performance hint can come once per draw.
TEST(Gl, RepeatedHintsAreToldOnce) {
  const auto context = gl::create_osmesa_context();
  std::vector<std::string> messages;
  context->route_debug_messages([&](const std::string& m) { messages.push_back(m); });
  const GladGLContext& gl = context->api();
  if (!gl.KHR_debug || !gl.DebugMessageInsert) GTEST_SKIP() << "no KHR_debug";
  const auto insert = [&](GLenum type, GLuint id, GLenum severity, const char* text) {
    gl.DebugMessageInsert(GL_DEBUG_SOURCE_APPLICATION, type, id, severity, -1, text);
  };
  for (int i = 0; i < 3; ++i) {
    insert(GL_DEBUG_TYPE_PERFORMANCE, 7, GL_DEBUG_SEVERITY_MEDIUM, "slow path");
    insert(GL_DEBUG_TYPE_PERFORMANCE, 8, GL_DEBUG_SEVERITY_MEDIUM, "another slow path");
    insert(GL_DEBUG_TYPE_ERROR, 9, GL_DEBUG_SEVERITY_HIGH, "broken");
    insert(GL_DEBUG_TYPE_OTHER, 10, GL_DEBUG_SEVERITY_NOTIFICATION, "fine");
  }
  ASSERT_EQ(messages.size(), 5u);
  EXPECT_NE(messages[0].find("slow path (its repeats are not shown)"), std::string::npos)
      << messages[0];
  EXPECT_NE(messages[1].find("another slow path"), std::string::npos) << messages[1];
  for (int i : {2, 3, 4}) EXPECT_NE(messages[i].find("OpenGL error"), std::string::npos);
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

} // namespace IRAD_UNITY_ID
} // namespace irad
