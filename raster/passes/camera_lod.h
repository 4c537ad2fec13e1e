#pragma once
// The camera's cluster hierarchy (core/mesh/hierarchy/mesh_clusters.h built with
// ClusterOptions::camera) on the GPU, for the G-buffer and the emitters: per view, the clusters the
// image's frustum meets, each drawn at the coarsest of its meshes whose error (the larger of its
// world-space distance from the original surface and its longest edge) is below kPixels of a pixel
// where it lies, so that what the camera draws stops growing with the triangles once they are finer
// than the pixels. The cut is of base meshes alone (no coarser levels), so neighbouring clusters
// meet along original edges: no crack lets the background through. Each tree holds one material,
// whose uniforms bind once before its ranges are drawn; the triangles of Mask and Blend materials,
// which the hierarchy leaves out, are drawn from the scene's own index buffer (GpuScene).
//
// A pixel's footprint at Euclidean distance d from the eye is d s cos^2(theta) for a pixel of
// angle s at the image's centre and theta off the axis: the allowed error per distance takes the
// corners' cos^2, the smallest. Orthographic cameras allow kPixels of their (constant) pixel.
//
// The pages of indices reach the GPU as views first draw them (the shadow passes' paging,
// raster/shadow/shadow_lod.h).
#include "core/camera/view.h"
#include "core/mesh/hierarchy/background_clusters.h"
#include "raster/shadow/shadow_lod.h"

#include <filesystem>
#include <functional>
#include <memory>
#include <vector>

namespace irad::gl {

class CameraLod {
public:
  // What a drawn mesh may change, in pixels at its distance: its distance from the surface and
  // its longest edge (ClusterOptions::camera), across which the normals and texture coordinates
  // are interpolated. On the 10M-triangle terrain at 256x256 (docs/performance.md "The camera's
  // hierarchy"), 2 pixels draw 3.1M of its 10M triangles for a relMSE against the path tracer of
  // 6.67e-5 (every triangle: 6.58e-5); 4 pixels 0.89M for 7.15e-5; half a pixel of distance
  // alone, without the edges, 0.27M for 3.5e-4 (bumps flattened, their shading with them).
  static constexpr float kPixels = 2.0f;

  // clusters: a camera hierarchy of gpu's scene (root_materials one per root).
  CameraLod(const GladGLContext& api, const GpuScene& gpu, MeshClusters clusters);

  // Chooses what `view` draws and copies the pages it needs to the GPU.
  void prepare(const View& view);
  // As GpuScene::draw_if, over what prepare chose: `bind(material)` before each material's
  // ranges, only those whose material satisfies `select`.
  void draw_if(const std::function<bool(const Material&)>& select,
               const std::function<void(const Material&)>& bind) const;

  // The triangles the prepared view draws from the hierarchy.
  std::size_t triangles() const;
  std::size_t gpu_bytes() const { return lod_.gpu_bytes(); }

private:
  struct Group { // the neighbouring roots of one material
    std::uint32_t material;
    std::vector<std::int32_t> roots;
    ClusterSelection selection; // what the prepared view draws
  };

  const GpuScene* gpu_;
  ShadowLod lod_;
  VertexArray vao_;
  std::vector<Group> groups_;
  ShadowLod::Plans plans_;
};

// A renderer's camera hierarchy: taken from a build started earlier or built through the cache
// at the first image that asks (core/mesh/hierarchy/background_clusters.h).
class CameraLodProvider {
public:
  // gpu must outlive this object. cache: as RasterOptions::hierarchy_cache; prebuilt: as
  // RasterOptions::camera_build (nullptr: none).
  CameraLodProvider(const GladGLContext& api, const GpuScene& gpu, std::filesystem::path cache,
                    std::shared_ptr<BackgroundClusters> prebuilt);
  // The hierarchy prepared for `view` (CameraLod::prepare), waiting for a prebuilt one or
  // building it on the first call.
  const CameraLod* prepared(const View& view);
  // What getting it cost this thread: "camera hierarchy <stage>" of a build here, or "camera
  // hierarchy wait" for a prebuilt one, then "camera hierarchy upload".
  const StageTimes& setup_times() const { return times_; }
  // Where it came from: the stages of a build beside, and what the cache did.
  const ClusterSource& source() const { return source_; }
  // The bytes of its pages on the GPU (0 before prepared()).
  std::size_t gpu_bytes() const { return lod_ ? lod_->gpu_bytes() : 0; }

private:
  const GladGLContext* api_;
  const GpuScene* gpu_;
  ClusterSource source_;
  std::unique_ptr<CameraLod> lod_;
  StageTimes times_;
};

// The error per unit of distance (perspective) or the error (orthographic: `floor`) kPixels
// allow in `view`.
struct PixelError {
  float per_distance = 0.0f, floor = 0.0f;
};
PixelError pixel_error(const View& view, float pixels);

// The four side planes a * p + d >= 0 of the frustum of `view_projection` (inside: -w <= x, y <= w
// in clip space).
std::array<glm::vec4, 4> frustum_planes(const glm::mat4& view_projection);

} // namespace irad::gl
