// irad_consumer SCENE: the installed library from a program of its own. Renders SCENE at 32x32
// with pt and with the raster at a few N, prints each image's mean, and checks that a missing
// file is an irad::Error naming it and that a cancelled render says so. Exit 0 when all hold.
#include <irad/irad.h>

#include <cmath>
#include <cstdio>
#include <string>

namespace {

double mean(const irad::Image& image) {
  double sum = 0.0;
  for (const glm::vec4& p : image.pixels()) sum += (p.r + p.g + p.b) / 3.0;
  return sum / static_cast<double>(image.pixels().size());
}

double render_mean(const irad::Scene& scene, irad::RenderOptions options, const char* what,
                   irad::Log& log) {
  options.size = {32, 32};
  const irad::RenderResult r = irad::render(scene, options, log);
  const double m = mean(r.image);
  std::printf("%s: mean %.6f (%zu VPLs)\n", what, m, r.vpls.vpls.size());
  return m;
}

bool missing_file_is_an_error(irad::Log& log) {
  try {
    irad::load_scene("no_such_scene.gltf", {}, log);
  } catch (const irad::Error& e) {
    std::printf("error: %s\n", e.what());
    return std::string(e.what()).find("no_such_scene.gltf") != std::string::npos;
  }
  return false;
}

bool cancel_stops(const irad::Scene& scene, irad::Log& log) {
  irad::RenderOptions options;
  options.estimator = irad::Estimator::Pt;
  options.size = {32, 32};
  std::size_t calls = 0;
  options.progress = [&calls](std::size_t, std::size_t) { ++calls; };
  options.cancel_requested = [&calls] { return calls > 0; };
  return irad::render(scene, options, log).cancelled;
}

} // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: irad_consumer SCENE.gltf\n");
    return 2;
  }
  try {
    irad::Log log;
    const irad::Scene scene = irad::load_scene(argv[1], {}, log);
    irad::RenderOptions pt;
    pt.estimator = irad::Estimator::Pt;
    pt.pt.spp = 16;
    bool ok = std::isfinite(render_mean(scene, pt, "pt 16 spp", log));
    for (const std::uint32_t paths : {4u, 16u, 64u}) {
      irad::RenderOptions raster;
      raster.walk.paths = paths;
      const std::string what = "raster " + std::to_string(paths) + " paths";
      const double m = render_mean(scene, raster, what.c_str(), log);
      ok = ok && std::isfinite(m) && m > 0.0;
    }
    ok = missing_file_is_an_error(log) && ok;
    ok = cancel_stops(scene, log) && ok;
    std::printf("%s\n", ok ? "ok" : "FAILED");
    return ok ? 0 : 1;
  } catch (const irad::Error& e) {
    std::fprintf(stderr, "irad_consumer: error: %s\n", e.what());
    return 1;
  }
}
