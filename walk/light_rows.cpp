#include "walk/light_rows.h"

#include "core/parallel_rows.h"
#include "core/rng.h"
#include "walk/vpl_gather.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace irad {

namespace {

// The pixels of the rows: a gx x gy grid of cells with the image's aspect, one pixel drawn
// uniformly in each.
std::vector<std::pair<int, int>> row_pixels(const View& view, std::size_t rows,
                                            std::uint64_t seed) {
  const double aspect = double(view.width) / double(view.height);
  const int gx = std::clamp(int(std::lround(std::sqrt(double(rows) * aspect))), 1, view.width);
  const int gy = std::clamp(int((rows + gx - 1) / std::size_t(gx)), 1, view.height);
  std::vector<std::pair<int, int>> pixels;
  for (int cy = 0; cy < gy; ++cy)
    for (int cx = 0; cx < gx; ++cx) {
      Pcg32 rng(seed, std::uint64_t(cy) * std::uint64_t(gx) + std::uint64_t(cx));
      const int x0 = cx * view.width / gx, x1 = (cx + 1) * view.width / gx;
      const int y0 = cy * view.height / gy, y1 = (cy + 1) * view.height / gy;
      if (x1 <= x0 || y1 <= y0) continue;
      pixels.emplace_back(x0 + int(rng.next_double() * (x1 - x0)),
                          y0 + int(rng.next_double() * (y1 - y0)));
    }
  return pixels;
}

} // namespace

ReducedMatrix light_rows(const Scene& scene, const RayScene& rays, const View& view,
                         const VplSet& vpls, const LightRowsOptions& options) {
  std::vector<ShadingPoint> points;
  for (const auto& [x, y] : row_pixels(view, options.rows, options.seed))
    if (const auto p = visible_point(scene, rays, view, x, y)) points.push_back(*p);
  ReducedMatrix m;
  m.rows = points.size();
  m.columns = vpls.vpls.size();
  m.values.assign(m.rows * m.columns, 0.0f);
  const float dmin = options.clamp * scene.bounds.diagonal();
  const float eps = rays.epsilon();
  parallel_rows(static_cast<int>(m.rows), options.threads, [&](int i) {
    // A cancelled render leaves the rows not started at 0 (a row: a few ms).
    if (options.cancel != nullptr && options.cancel->load(std::memory_order_relaxed)) return;
    const ShadingPoint& p = points[static_cast<std::size_t>(i)];
    const glm::vec3 k = p.albedo * std::numbers::inv_pi_v<float>;
    for_each_vpl_irradiance(rays, p, vpls, dmin, eps, [&](std::size_t j, const glm::vec3& term) {
      const glm::vec3 c = k * term;
      m.column(j)[i] = c.x + c.y + c.z;
    });
  });
  return m;
}

} // namespace irad
