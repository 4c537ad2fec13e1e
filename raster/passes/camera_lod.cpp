#include "raster/passes/camera_lod.h"

#include "core/util/error.h"
#include "core/util/freed_memory.h"
#include "raster/raster_renderer.h"

#include <algorithm>

namespace irad::gl {

PixelError pixel_error(const View& view, float pixels) {
  const glm::mat4& p = view.projection;
  // A pixel's extent at unit distance on the axis (perspective: 2 tan(fovy / 2) / height) or
  // in the world (orthographic: 2 ymag / height).
  const float pixel = 2.0f / (p[1][1] * static_cast<float>(std::max(view.height, 1)));
  if (view.orthographic) return {0.0f, pixels * pixel};
  // cos^2 of the corners' angle off the axis: 1 / (1 + tan^2 x + tan^2 y).
  const float tx = 1.0f / p[0][0], ty = 1.0f / p[1][1];
  const float corner = 1.0f / (1.0f + tx * tx + ty * ty);
  return {pixels * pixel * corner, 0.0f};
}

std::array<glm::vec4, 4> frustum_planes(const glm::mat4& view_projection) {
  const glm::mat4 t = glm::transpose(view_projection); // t[i]: row i
  return {t[3] + t[0], t[3] - t[0], t[3] + t[1], t[3] - t[1]};
}

CameraLod::CameraLod(const GladGLContext& api, const GpuScene& gpu, MeshClusters clusters)
    : gpu_(&gpu), lod_(api, gpu, std::move(clusters), true), vao_(lod_.vertex_array()) {
  const MeshClusters& c = lod_.clusters();
  if (c.root_materials.size() != c.roots.size())
    throw Error(gpu.scene().source, "camera hierarchy", "not one material per tree");
  for (std::size_t r = 0; r < c.roots.size(); ++r) {
    const std::uint32_t m = c.root_materials[r];
    if (groups_.empty() || groups_.back().material != m) groups_.push_back({m, {}, {}});
    groups_.back().roots.push_back(c.roots[r]);
  }
}

void CameraLod::prepare(const View& view) {
  const std::array<glm::vec4, 4> planes = frustum_planes(view.projection * view.view);
  const PixelError allowed = pixel_error(view, kPixels);
  std::vector<std::vector<ClusterPick>> picks(groups_.size());
  for (std::size_t g = 0; g < groups_.size(); ++g)
    lod_.pick(groups_[g].roots, planes, view.eye, allowed.per_distance, allowed.floor, plans_,
              picks[g]);
  lod_.make_resident(picks);
  for (std::size_t g = 0; g < groups_.size(); ++g) lod_.select(picks[g], groups_[g].selection);
}

void CameraLod::draw_if(const std::function<bool(const Material&)>& select,
                        const std::function<void(const Material&)>& bind) const {
  const Scene& scene = gpu_->scene();
  for (const Group& g : groups_) {
    const Material& m = scene.materials[g.material];
    if (g.selection.triangles == 0 || !select(m)) continue;
    bind(m);
    lod_.draw(g.selection, vao_);
  }
  // What the hierarchy leaves out: the Mask and Blend materials' triangles.
  gpu_->draw_if([&](const Material& m) { return m.alpha_mode != AlphaMode::Opaque && select(m); },
                bind);
}

std::size_t CameraLod::triangles() const {
  std::size_t n = 0;
  for (const Group& g : groups_) n += g.selection.triangles;
  return n;
}

CameraLodProvider::CameraLodProvider(const GladGLContext& api, const GpuScene& gpu,
                                     std::filesystem::path cache,
                                     std::shared_ptr<BackgroundClusters> prebuilt)
    : api_(&api), gpu_(&gpu), source_("camera hierarchy ", std::move(cache), std::move(prebuilt)) {}

const CameraLod* CameraLodProvider::prepared(const View& view) {
  if (!lod_) {
    MeshClusters clusters = source_.get(gpu_->scene(), camera_cluster_options(), times_);
    const auto start = StageTimes::Clock::now();
    lod_ = std::make_unique<CameraLod>(*api_, *gpu_, std::move(clusters));
    release_freed_memory(); // the build's transients
    times_.lap("camera hierarchy upload", start);
  }
  lod_->prepare(view);
  return lod_.get();
}

} // namespace irad::gl
