// The shadow atlases drawn on helper threads with contexts of their own
// (raster/shadow/shadow_helpers.h, raster/context/gl_thread.h): a job runs on its thread with
// its context current and sees the creator's objects; an error reaches the caller; the image is
// the one the renderer's own context draws, bit for bit, in every way the atlas draws (the
// hierarchy, every triangle, alpha-tested materials), and a cancelled render stops cleanly.
#include "core/camera/view.h"
#include "core/image/image_metrics.h"
#include "core/util/error.h"
#include "raster/context/gl_context.h"
#include "raster/context/gl_objects.h"
#include "raster/context/gl_thread.h"
#include "raster/raster_renderer.h"
#include "raster/scene/gpu_scene.h"
#include "raster/shadow/shadow_helpers.h"
#include "tests/test_rooms.h"
#include "walk/estimators/visibility_tracer.h"
#include "walk/estimators/vpl_tracer.h"
#include "walk/rays/ray_scene.h"
#include "walk/vpls/quasi_random_walk.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <thread>

namespace irad {
namespace IRAD_UNITY_ID {

using test_support::add_room;

Log quiet_log() {
  return Log([](const std::string&) {});
}

// The box [lo, hi], its six quads facing out.
void add_box(Scene& s, const glm::vec3& lo, const glm::vec3& hi, std::uint32_t material) {
  const float x0 = lo.x, y0 = lo.y, z0 = lo.z, x1 = hi.x, y1 = hi.y, z1 = hi.z;
  add_quad(s, {x0, y0, z0}, {x1, y0, z0}, {x1, y0, z1}, {x0, y0, z1}, material); // -y
  add_quad(s, {x0, y1, z0}, {x0, y1, z1}, {x1, y1, z1}, {x1, y1, z0}, material); // +y
  add_quad(s, {x0, y0, z0}, {x0, y1, z0}, {x1, y1, z0}, {x1, y0, z0}, material); // -z
  add_quad(s, {x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}, material); // +z
  add_quad(s, {x0, y0, z0}, {x0, y0, z1}, {x0, y1, z1}, {x0, y1, z0}, material); // -x
  add_quad(s, {x1, y0, z0}, {x1, y1, z0}, {x1, y1, z1}, {x1, y0, z1}, material); // +x
}

// A 4 m room lit from a ceiling panel; with `boxes`, over a field of 32 x 32 small boxes (12,288
// triangles that the hierarchy cannot simplify away, as a game level's props) with two
// alpha-tested panels over them: one cut out (base alpha 0.2 < cutoff 0.5), one kept. Its VPLs
// (96 paths) and a 64x64 view of the field.
struct BoxField {
  Scene s;
  VplSet vpls;
  View view;
  // mirror: the x = 0 wall carries a mirror (its VPLs' batches draw the reflected scene too).
  // sun: a directional light besides (its VPL shades in a batch of its own, from the
  // orthographic atlas).
  explicit BoxField(bool boxes = true, bool mirror = false, bool sun = false);
};

void add_boxes(Scene& s, std::uint32_t wall) {
  for (int i = 0; i < 32; ++i)
    for (int j = 0; j < 32; ++j) {
      const glm::vec3 lo(0.2f + 0.11f * float(i), 0.0f, 0.2f + 0.11f * float(j));
      add_box(s, lo, lo + glm::vec3(0.08f, 0.05f + 0.01f * float((i * 7 + j * 3) % 11), 0.08f),
              wall);
    }
  for (int k = 0; k < 2; ++k) {
    const std::uint32_t m = add_material(s, glm::vec3(0.5f));
    s.materials[m].alpha_mode = AlphaMode::Mask;
    s.materials[m].alpha_cutoff = 0.5f;
    s.materials[m].base_alpha = k == 0 ? 0.2f : 1.0f;
    const float x = 0.8f + 1.6f * static_cast<float>(k);
    add_quad(s, {x, 1.0f, 0.8f}, {x + 0.8f, 1.0f, 0.8f}, {x + 0.8f, 1.0f, 3.2f}, {x, 1.0f, 3.2f},
             m);
  }
}

BoxField::BoxField(bool boxes, bool mirror, bool sun) {
  const std::uint32_t wall = add_material(s, glm::vec3(0.6f));
  const std::uint32_t light = add_material(s, glm::vec3(0.6f), glm::vec3(8.0f));
  add_room(s, {0.0f, 0.0f, 0.0f}, {4.0f, 3.0f, 4.0f}, wall);
  add_quad(s, {1.5f, 2.999f, 1.5f}, {2.5f, 2.999f, 1.5f}, {2.5f, 2.999f, 2.5f},
           {1.5f, 2.999f, 2.5f}, light);
  if (boxes) add_boxes(s, wall);
  if (mirror) {
    const std::uint32_t m = add_material(s, glm::vec3(0.9f));
    s.materials[m].specular = true;
    add_quad(s, {0.001f, 0.5f, 1.0f}, {0.001f, 0.5f, 3.0f}, {0.001f, 2.5f, 3.0f},
             {0.001f, 2.5f, 1.0f}, m); // facing +x
  }
  if (sun) {
    PunctualLight l;
    l.kind = PunctualLight::Kind::Directional;
    l.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
    l.intensity = glm::vec3(0.05f); // most paths still start at the panel
    s.lights.push_back(l);
  }
  finish(s);
  Log log = quiet_log();
  vpls = quasi_random_walk(s, RayScene(s), {96, 64}, log);
  view =
      make_view(look_at({0.3f, 2.2f, 0.3f}, {2.5f, 0.2f, 2.5f}, {0, 1, 0}, 1.2f), s.bounds, 64, 64);
}

class GlThreadOn : public ::testing::TestWithParam<GlBackend> {};

TEST_P(GlThreadOn, RunsJobsInOrderInAContextThatSharesObjects) {
  std::unique_ptr<gl::Context> context = gl::create_context(GetParam());
  const GladGLContext& api = context->api();
  const gl::Buffer buffer = gl::make_buffer(api);
  api.BindBuffer(GL_ARRAY_BUFFER, buffer.get());
  const float data[4] = {1.0f, 2.0f, 3.0f, 4.0f};
  api.BufferData(GL_ARRAY_BUFFER, sizeof(data), data, GL_STATIC_DRAW);
  api.Finish();
  const std::thread::id here = std::this_thread::get_id();
  std::vector<int> order;
  {
    gl::GlThread thread(context->make_shared());
    for (int k = 0; k < 3; ++k)
      thread.post([&order, k, here, &buffer](const GladGLContext& gl) {
        EXPECT_NE(std::this_thread::get_id(), here);
        // The creator's buffer, read through this thread's context.
        float back[4] = {};
        gl.BindBuffer(GL_ARRAY_BUFFER, buffer.get());
        gl.GetBufferSubData(GL_ARRAY_BUFFER, 0, sizeof(back), back);
        EXPECT_EQ(back[3], 4.0f);
        order.push_back(k);
      });
    std::future<void> failed = thread.post(
        [](const GladGLContext&) { throw Error("", "helper job", "failed on purpose"); });
    EXPECT_THROW(failed.get(), Error);
    thread.run([&order](const GladGLContext&) { order.push_back(3); }); // still running
  }
  EXPECT_EQ(order, (std::vector<int>{0, 1, 2, 3}));
  api.BindBuffer(GL_ARRAY_BUFFER, 0);
  context->check("after the helper thread"); // the creator's context is still current and sound
}

INSTANTIATE_TEST_SUITE_P(GlThread, GlThreadOn, ::testing::Values(GlBackend::OsMesa, GlBackend::Egl),
                         [](const auto& test) {
                           return std::string(test.param == GlBackend::Egl ? "Egl" : "OsMesa");
                         });

// Renders box_field() with and without helpers for one way of drawing the atlas.
struct Pair {
  Image own, helped;
  RasterTimings own_t, helped_t;
};

Pair render_both(const BoxField& f, ShadowLodMode mode, GlBackend backend = GlBackend::OsMesa,
                 ShadowPlanes planes = ShadowPlanes::Auto) {
  Pair p;
  RasterOptions o;
  // The helpers' batch (BatchedPasses::kHelperBatch): the renderer's own context then draws the
  // same batches as the helpers (larger ones order the faces' clusters into other rounds).
  o.batch = 16;
  o.backend = backend;
  o.shadow_lod.mode = mode;
  o.shadow_lod.planes = planes;
  o.hierarchy_cache.clear();
  o.shadow_helpers = 0;
  p.own = RasterRenderer(f.s, o).render(f.view, f.vpls, &p.own_t);
  o.shadow_helpers = 2;
  p.helped = RasterRenderer(f.s, o).render(f.view, f.vpls, &p.helped_t);
  return p;
}

TEST(ShadowHelpers, TheSameImageAsTheRenderersOwnContext) {
  const BoxField f;
  for (ShadowLodMode mode : {ShadowLodMode::On, ShadowLodMode::Off}) { // Cull: On's code
    const Pair p = render_both(f, mode);
    const char* name = mode == ShadowLodMode::On ? "on" : "off";
    std::printf("box field, shadow-lod %s: %zu VPLs, %zu hierarchy triangles, helpers %d\n", name,
                p.helped_t.passes, p.helped_t.shadow_triangles, p.helped_t.shadow_helpers);
    // Made: a batch draws >= 8000 triangles per VPL (measured over all VPLs: 11.4k; off draws
    // all 12,306 in every face) and 8 or more batches of 16 follow the first.
    EXPECT_EQ(p.helped_t.shadow_helpers, 2) << name;
    EXPECT_EQ(p.own_t.shadow_helpers, 0) << name;
    EXPECT_EQ(p.helped_t.passes, p.own_t.passes) << name;
    EXPECT_EQ(p.helped_t.shadow_triangles, p.own_t.shadow_triangles) << name;
    // The same program, hierarchy and faces in either context: the same bits.
    EXPECT_TRUE(p.own.pixels() == p.helped.pixels()) << name;
    bool lit = false;
    for (const glm::vec4& px : p.helped.pixels()) lit = lit || px.r > 0.0f;
    EXPECT_TRUE(lit) << name;
  }
}

// With the default batch (64), the first batch is drawn here in the helpers' size
// (BatchedPasses::kHelperBatch) and decides them; they then draw the rest from where it ended:
// every VPL once, and the image of the renderer's own context drawing all of them in batches of
// 16 (measured: the same bits; in batches of 64, relMSE 5.5e-7: the blocks sit elsewhere in a
// larger atlas).
TEST(ShadowHelpers, TakeOverWhereTheFirstBatchEnded) {
  const BoxField f;
  RasterOptions o;
  o.hierarchy_cache.clear();
  ASSERT_GT(o.batch, 16);
  o.shadow_helpers = 2;
  RasterTimings helped_t, own_t;
  const Image helped = RasterRenderer(f.s, o).render(f.view, f.vpls, &helped_t);
  o.shadow_helpers = 0;
  o.batch = 16;
  const Image own = RasterRenderer(f.s, o).render(f.view, f.vpls, &own_t);
  const ImageMetrics m = compare_images(helped, own);
  std::printf("box field, batch %d with helpers: %zu VPLs, relMSE %.3g against batches of 16, "
              "shadow triangles %zu against %zu\n",
              RasterOptions{}.batch, helped_t.passes, m.relmse, helped_t.shadow_triangles,
              own_t.shadow_triangles);
  EXPECT_EQ(helped_t.shadow_helpers, 2);
  EXPECT_EQ(helped_t.passes, own_t.passes);
  EXPECT_EQ(helped_t.shadow_triangles, own_t.shadow_triangles);
  EXPECT_LT(m.relmse, 1e-9);
}

TEST(ShadowHelpers, TheSameImageThroughEgl) {
  const Pair p = render_both(BoxField(), ShadowLodMode::On, GlBackend::Egl);
  EXPECT_EQ(p.helped_t.shadow_helpers, 2);
  EXPECT_TRUE(p.own.pixels() == p.helped.pixels());
}

TEST(ShadowHelpers, TheSameImageWithMirroredVpls) {
  const BoxField f(true, true);
  ASSERT_TRUE(std::any_of(f.vpls.vpls.begin(), f.vpls.vpls.end(),
                          [](const Vpl& v) { return v.mirror >= 0; }));
  const Pair p = render_both(f, ShadowLodMode::On);
  EXPECT_EQ(p.helped_t.shadow_helpers, 2);
  EXPECT_TRUE(p.own.pixels() == p.helped.pixels());
}

// A batch of directional VPLs alone, drawn where the helpers draw the cubes, binds a cube atlas
// and its gradients too when the occluder planes are on (a sun in zdm2 at 128x128 threw "shadow
// lookup without gradients").
TEST(ShadowHelpers, TheSameImageWithADirectionalLightAndOccluderPlanes) {
  BoxField f(true, false, true);
  // The sun's VPLs last, split in 40 (a batch of directional VPLs alone, after the helpers
  // started).
  std::vector<Vpl>& v = f.vpls.vpls;
  const auto sun = std::stable_partition(
      v.begin(), v.end(), [](const Vpl& x) { return x.kind != VplKind::Directional; });
  ASSERT_NE(sun, v.end());
  Vpl light = *sun; // one direction: their sum
  for (auto d = sun + 1; d != v.end(); ++d) light.intensity += d->intensity;
  v.erase(sun, v.end());
  for (int k = 0; k < 40; ++k) {
    v.push_back(light);
    v.back().intensity = light.intensity / 40.0f;
  }
  const Pair p = render_both(f, ShadowLodMode::On, GlBackend::OsMesa, ShadowPlanes::On);
  EXPECT_EQ(p.helped_t.shadow_helpers, 2);
  EXPECT_TRUE(p.own.pixels() == p.helped.pixels());
}

TEST(ShadowHelpers, ErrorsReachTheCallerAndLeaveTheContextSound) {
  const BoxField f(false);
  std::unique_ptr<gl::Context> context = gl::create_context(GlBackend::OsMesa);
  const gl::GpuScene gpu(context->api(), f.s);
  gl::ShadowHelpers::AtlasShape shape{
      64, 4, 2, f.s.bounds, gl::MaterialFeatures::of(f.s), {ShadowLodMode::Off}};
  // An atlas this GL cannot hold: made on the threads, the error comes back from the constructor.
  gl::ShadowHelpers::AtlasShape huge = shape;
  huge.resolution = 8192;
  EXPECT_THROW(gl::ShadowHelpers(*context, 2, huge, nullptr), Error);
  context->check("after the failed helpers");

  gl::ShadowHelpers helpers(*context, 2, shape, nullptr);
  Vpl point;
  point.kind = VplKind::Point; // two blocks each: three do not fit the atlas's two
  point.position = glm::vec3(2.0f, 1.5f, 2.0f);
  point.intensity = glm::vec3(1.0f);
  gl::ShadowHelpers::Job failing, fine, left;
  failing.vpls = {&point, &point, &point};
  fine.vpls = {&point};
  left.vpls = {&point};
  helpers.start(0, failing, gpu, false);
  helpers.start(1, fine, gpu, false);
  helpers.start(0, left, gpu, false);
  EXPECT_THROW(helpers.finish(failing), Error);
  const gl::ShadowHelpers::Drawn& d = helpers.finish(fine);
  EXPECT_NE(d.texture, 0u);
  EXPECT_EQ(d.blocks.size(), 1u);
  helpers.abandon(left); // never read: waited for, its fence dropped
  EXPECT_FALSE(left.done.valid());
  context->check("after the helpers' jobs");
}

TEST(ShadowHelpers, FewTrianglesPerVplMakeNone) {
  const BoxField f(false);
  RasterOptions o;
  o.hierarchy_cache.clear();
  o.shadow_helpers = 2;
  RasterTimings t;
  RasterRenderer(f.s, o).render(f.view, f.vpls, &t);
  EXPECT_EQ(t.shadow_helpers, 0); // a room of 14 triangles: the hand-over would cost more
}

// Given a ray tracer, Auto on llvmpipe takes rays where VPLs draw many triangles against the
// pixels each shades (BatchedPasses::rays_pay: the box field's probes about 11k against 4096
// pixels), instead of helpers; the image is then nearer rt-vpl over the same VPLs. The empty room
// (14 triangles) keeps the maps. Measured (llvmpipe, 64x64, every pixel lit by every VPL):
// relMSE against rt-vpl 1.7e-3 with rays (the pixels whose G-buffer surface is not the primary
// ray's: the boxes' many silhouettes), 1.17e-2 with maps.
TEST(ShadowHelpers, ManyTrianglesPerVplTakeRaysWhereATracerIsGiven) {
  for (const bool boxes : {true, false}) {
    const BoxField f(boxes);
    const RayScene rays(f.s);
    RasterOptions o;
    o.hierarchy_cache.clear();
    o.interleave = 1;
    o.shadow_helpers = 2;
    const float dmin = o.clamp * f.s.bounds.diagonal();
    o.visibility_tracer = [&rays, dmin](const VisibilityRequest& r) {
      trace_visibility(rays, dmin, r);
    };
    RasterTimings t;
    const Image image = RasterRenderer(f.s, o).render(f.view, f.vpls, &t);
    o.visibility = Visibility::Maps;
    RasterTimings maps_t;
    const Image maps = RasterRenderer(f.s, o).render(f.view, f.vpls, &maps_t);
    const Image exact = trace_vpls(f.s, rays, f.view, f.vpls, {o.clamp});
    const double by_auto = compare_images(image, exact).relmse;
    const double by_maps = compare_images(maps, exact).relmse;
    std::printf("box field %d: auto %s (relMSE %.3g against rt-vpl), maps %.3g, helpers %d\n",
                boxes, t.ray_visibility ? "rays" : "maps", by_auto, by_maps, maps_t.shadow_helpers);
    EXPECT_EQ(t.ray_visibility, boxes);
    EXPECT_EQ(t.shadow_helpers, 0);
    EXPECT_EQ(t.passes, maps_t.passes);
    EXPECT_FALSE(maps_t.ray_visibility);
    if (boxes) {
      EXPECT_EQ(maps_t.shadow_helpers, 2);
      EXPECT_GT(t.visibility_seconds, 0.0);
      EXPECT_LT(by_auto, 0.2 * by_maps);
    } else {
      EXPECT_TRUE(image.pixels() == maps.pixels());
    }
  }
}

TEST(ShadowHelpers, ACancelledRenderWaitsForTheJobsStarted) {
  const BoxField f;
  std::atomic<bool> cancel{false};
  RasterOptions o;
  o.shadow_lod.mode = ShadowLodMode::Cull;
  o.hierarchy_cache.clear();
  o.shadow_helpers = 2;
  o.cancel = &cancel;
  RasterRenderer raster(f.s, o);
  RasterTimings t;
  // Cancelled once 12 batches are shaded: the helpers have up to 4 more started.
  const Image image = raster.render(f.view, f.vpls, &t, [&cancel](std::size_t done, std::size_t) {
    if (done >= 12 * 16) cancel = true;
  });
  EXPECT_EQ(t.shadow_helpers, 2);
  EXPECT_GE(t.passes, 12u * 16u);
  EXPECT_LT(t.passes, f.vpls.vpls.size());
  for (const glm::vec4& px : image.pixels()) ASSERT_TRUE(std::isfinite(px.r));
  // The renderer and its helpers draw on afterwards.
  cancel = false;
  RasterTimings again;
  raster.render(f.view, f.vpls, &again);
  EXPECT_GT(again.passes, t.passes);
}

} // namespace IRAD_UNITY_ID
} // namespace irad
