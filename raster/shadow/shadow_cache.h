#pragma once
// Shadow maps kept per light path (RasterRenderer::cache_path / render_cached, the cached
// walkthrough): each path slot's VPLs get their cubes drawn by a ShadowAtlas, batch by batch,
// and copied block by block into pages that keep them until the slot is drawn again, so the
// deferred passes (raster/passes/deferred_shader.h) shade every kept VPL from a moving camera
// without redrawing a shadow map. A page is a DEPTH_COMPONENT32F texture (and the RG16F
// gradients beside it, raster/glsl/cube_glsl.h) in ShadowAtlas's layout
// (blocks of (2R + 2h) x 2h texels; a surface VPL takes one, any other two); a slot's blocks go
// back to the free list when the slot is replaced, so a full ring allocates nothing per frame.
// A page grows (doubling its rows, its blocks copied) up to the texture size before a second one
// is started: one page, one texture per deferred draw, for every kept VPL of a usual ring.
#include "core/lights/vpl.h"
#include "core/scene/bounds.h"
#include "raster/context/gl_objects.h"
#include "raster/passes/batched_passes.h"
#include "raster/scene/gpu_scene.h"
#include "raster/shadow/shadow_atlas.h"

#include <cstdint>
#include <optional>
#include <vector>

namespace irad::gl {

class ShadowCache {
public:
  // Cubes of resolution^2 faces, drawn `batch` VPLs at a time (ShadowAtlas::capacity's limits).
  ShadowCache(const GladGLContext& api, int resolution, int batch, const Bounds& bounds,
              const MaterialFeatures& features);

  int resolution() const { return resolution_; }
  // Replaces the maps of `slot` by the cubes of `vpls` (each carries light; no directional VPL:
  // an orthographic map is drawn per image), and keeps the glossy ones' lobes (Vpl::lobe indexes
  // `lobes`). Changes the bound framebuffers and viewport.
  void store(std::uint32_t slot, const std::vector<Vpl>& vpls, const GpuScene& gpu,
             const std::vector<VplLobe>& lobes = {});

  // The kept VPLs page by page (AtlasVpl::set 0, lobe the kept one; valid until the next store).
  struct Page {
    ShadowLookup lookup;
    std::vector<AtlasVpl> vpls;
  };
  std::vector<Page> pages() const;
  std::size_t bytes() const; // GPU memory of the pages

private:
  struct Block {
    int page, index;
  };
  struct Kept {
    Vpl vpl;
    glm::mat3 frame;
    float far;
    Block blocks[2];
    int count;                   // blocks taken
    std::optional<VplLobe> lobe; // a glossy VPL's
  };
  // `count` free blocks of one page (a VPL's blocks are looked up in one texture), in a new page
  // when no page has them.
  void allocate(int count, Block* out);
  void add_page();
  // Doubles the rows of the last page (at most max_rows_), keeping its blocks where they are.
  void grow_last_page();
  // A page texture and its framebuffer of `rows` rows of blocks.
  void make_page(int rows, Texture& texture, Texture& gradient, Framebuffer& fbo) const;
  glm::ivec2 origin(int index) const {
    return glm::ivec2(index % columns_, index / columns_) * block_;
  }
  // Copies the block at texel `from` of the atlas just drawn (the read framebuffer) into `to`.
  void copy_block(glm::ivec2 from, Block to);

  const GladGLContext* api_;
  int resolution_;
  glm::ivec2 block_;       // block size in texels
  int columns_, max_rows_; // blocks per row of a page; rows of the largest page
  ShadowAtlas atlas_;
  Framebuffer read_fbo_; // the atlas as read framebuffer
  std::vector<Texture> pages_;
  std::vector<Texture> gradients_; // per page, as ShadowAtlas::gradient_texture()
  std::vector<Framebuffer> page_fbos_;
  std::vector<int> rows_;              // per page
  std::vector<std::vector<int>> free_; // per page, the free blocks' indices
  std::vector<std::vector<Kept>> slots_;
};

} // namespace irad::gl
