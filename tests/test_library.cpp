// The library's API (lib/irad/irad.h) as a program calls it: a scene loaded once renders many
// times with the image render_file gives; progress reaches its total; cancellation by the
// callback or the flag stops at once and says so; errors name the file and the element.
#include "irad/irad.h"
#include "tests/test_paths.h"

#include <atomic>
#include <gtest/gtest.h>
#include <string>

namespace IRAD_UNITY_ID {

const std::string kBox = std::string(IRAD_SOURCE_DIR) + "/data/cornell_box.gltf";

irad::RenderOptions small(irad::Estimator estimator) {
  irad::RenderOptions o;
  o.estimator = estimator;
  o.size = {24, 16};
  o.walk.paths = 16;
  o.pt.spp = 2;
  return o;
}

bool same_pixels(const irad::Image& a, const irad::Image& b) {
  return a.width() == b.width() && a.height() == b.height() && a.pixels() == b.pixels();
}

TEST(Library, OneSceneRendersAsRenderFileDoes) {
  irad::Log log([](const std::string&) {});
  const irad::Scene scene = irad::load_scene(kBox, {}, log);
  for (const auto e : {irad::Estimator::Raster, irad::Estimator::RtVpl, irad::Estimator::Pt}) {
    const irad::RenderResult a = irad::render(scene, small(e), log);
    const irad::RenderResult b = irad::render(scene, small(e), log);
    irad::RenderRequest request;
    request.scene_path = kBox;
    request.render = small(e);
    const irad::FileRender f = irad::render_file(request, log);
    EXPECT_TRUE(same_pixels(a.image, b.image)) << irad::estimator_name(e);
    EXPECT_TRUE(same_pixels(a.image, f.result.image)) << irad::estimator_name(e);
    EXPECT_EQ(a.image.width(), 24);
    EXPECT_FALSE(a.cancelled);
    EXPECT_EQ(f.scene.triangle_count(), scene.triangle_count());
  }
}

TEST(Library, ProgressReachesItsTotal) {
  irad::Log log([](const std::string&) {});
  const irad::Scene scene = irad::load_scene(kBox, {}, log);
  for (const auto e : {irad::Estimator::Raster, irad::Estimator::Pt}) {
    irad::RenderOptions o = small(e);
    o.pt.threads = 1; // pt reports the rows the calling thread finished
    std::size_t last_done = 0, last_total = 0, calls = 0;
    o.progress = [&](std::size_t done, std::size_t total) {
      EXPECT_GE(done, last_done);
      last_done = done;
      last_total = total;
      ++calls;
    };
    irad::render(scene, o, log);
    EXPECT_GT(calls, 0u) << irad::estimator_name(e);
    EXPECT_EQ(last_done, last_total) << irad::estimator_name(e);
  }
}

TEST(Library, CancellationStopsTheRender) {
  irad::Log log([](const std::string&) {});
  const irad::Scene scene = irad::load_scene(kBox, {}, log);
  for (const auto e : {irad::Estimator::Raster, irad::Estimator::RtVpl, irad::Estimator::Pt}) {
    irad::RenderOptions by_callback = small(e);
    by_callback.cancel_requested = [] { return true; };
    const irad::RenderResult a = irad::render(scene, by_callback, log);
    EXPECT_TRUE(a.cancelled) << irad::estimator_name(e);
    EXPECT_EQ(a.image.width(), 0) << "nothing rendered: cancelled before the first stage";

    const std::atomic<bool> flag{true};
    irad::RenderOptions by_flag = small(e);
    by_flag.cancel = &flag;
    EXPECT_TRUE(irad::render(scene, by_flag, log).cancelled) << irad::estimator_name(e);
  }
}

TEST(Library, CancellationAfterTheFirstProgressKeepsWhatWasDone) {
  irad::Log log([](const std::string&) {});
  const irad::Scene scene = irad::load_scene(kBox, {}, log);
  for (const auto e : {irad::Estimator::Raster, irad::Estimator::Pt}) {
    irad::RenderOptions o = small(e);
    o.pt.threads = 1; // pt: rows one after the other, so the cancel comes before the last
    o.raster.batch = 1;
    o.raster.interleave = 1; // raster: one pass per VPL
    std::size_t calls = 0, total = 0;
    o.progress = [&](std::size_t, std::size_t t) {
      ++calls;
      total = t;
    };
    o.cancel_requested = [&] { return calls > 0; };
    const irad::RenderResult r = irad::render(scene, o, log);
    EXPECT_TRUE(r.cancelled) << irad::estimator_name(e);
    EXPECT_EQ(r.image.width(), 24) << irad::estimator_name(e);
    if (e == irad::Estimator::Pt) // the rows after the first were not started: alpha 0
      EXPECT_EQ(r.image.at(0, 15).a, 0.0f);
    else
      EXPECT_LT(calls, total);
  }
}

TEST(Library, ErrorsNameTheFileAndTheElement) {
  irad::Log log([](const std::string&) {});
  const irad::Scene scene = irad::load_scene(kBox, {}, log);
  irad::RenderOptions o = small(irad::Estimator::Raster);
  o.camera = "nope";
  try {
    irad::render(scene, o, log);
    FAIL() << "no error";
  } catch (const irad::Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind(kBox + ": --camera: no camera 'nope'", 0), 0u)
        << e.what();
  }
  irad::SceneOptions limits;
  limits.limits.max_triangles = 1;
  EXPECT_THROW(irad::load_scene(kBox, limits, log), irad::Error);
  EXPECT_THROW(irad::parse_estimator("nope"), irad::Error);
}

} // namespace
