#include "raster/shadow/shadow_cache.h"

#include <algorithm>

namespace irad::gl {

namespace {

constexpr int kMaxPageSide = 4096;
// Blocks of a new page: 16 blocks of 64^2 faces are 1.6 MB (depth and gradient).
constexpr int kFirstPageBlocks = 16;

int max_page_side(const GladGLContext& api) {
  GLint texture = 0;
  api.GetIntegerv(GL_MAX_TEXTURE_SIZE, &texture);
  return std::min(kMaxPageSide, static_cast<int>(texture));
}

} // namespace

ShadowCache::ShadowCache(const GladGLContext& api, int resolution, int batch, const Bounds& bounds,
                         const MaterialFeatures& features)
    : api_(&api), resolution_(resolution), block_(ShadowAtlas::block_size(resolution)),
      columns_(std::clamp(max_page_side(api) / block_.x, 1, 16)),
      max_rows_(std::max(1, max_page_side(api) / block_.y)),
      atlas_(api, resolution, batch, 2 * batch, bounds, features),
      read_fbo_(make_framebuffer(api)) {}

void ShadowCache::make_page(int rows, Texture& texture, Texture& gradient, Framebuffer& fbo) const {
  const GladGLContext& api = *api_;
  const glm::ivec2 size = glm::ivec2(columns_, rows) * block_;
  texture = make_depth_texture(api, size.x, size.y);
  fbo = make_depth_framebuffer(api, texture.get(), "shadow cache page");
  gradient = make_gradient_texture(api, size.x, size.y); // as ShadowAtlas's
  api.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, gradient.get(), 0);
  api.DrawBuffer(GL_COLOR_ATTACHMENT0);
  api.ReadBuffer(GL_COLOR_ATTACHMENT0);
  check_framebuffer(api, "shadow cache page");
}

void ShadowCache::add_page() {
  const int rows = std::min(max_rows_, (kFirstPageBlocks + columns_ - 1) / columns_);
  pages_.emplace_back();
  gradients_.emplace_back();
  page_fbos_.emplace_back();
  make_page(rows, pages_.back(), gradients_.back(), page_fbos_.back());
  rows_.push_back(rows);
  std::vector<int> all(static_cast<std::size_t>(columns_ * rows));
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(all.size() - 1 - i);
  free_.push_back(std::move(all));
}

void ShadowCache::grow_last_page() {
  const GladGLContext& api = *api_;
  const std::size_t p = pages_.size() - 1;
  const int rows = rows_[p], grown = std::min(max_rows_, 2 * rows);
  Texture texture, gradient;
  Framebuffer fbo;
  make_page(grown, texture, gradient, fbo);
  const glm::ivec2 size = glm::ivec2(columns_, rows) * block_;
  api.Disable(GL_SCISSOR_TEST);
  api.BindFramebuffer(GL_READ_FRAMEBUFFER, page_fbos_[p].get());
  api.BindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo.get());
  api.BlitFramebuffer(0, 0, size.x, size.y, 0, 0, size.x, size.y,
                      GL_DEPTH_BUFFER_BIT | GL_COLOR_BUFFER_BIT, GL_NEAREST);
  pages_[p] = std::move(texture);
  gradients_[p] = std::move(gradient);
  page_fbos_[p] = std::move(fbo);
  rows_[p] = grown;
  for (int i = columns_ * grown - 1; i >= columns_ * rows; --i) free_[p].push_back(i);
}

void ShadowCache::allocate(int count, Block* out) {
  std::size_t page = 0;
  while (page < free_.size() && static_cast<int>(free_[page].size()) < count) ++page;
  const auto enough = [&](std::size_t p) { return static_cast<int>(free_[p].size()) >= count; };
  if (page == free_.size() && !pages_.empty()) { // grow the last page while it can
    page = pages_.size() - 1;
    while (!enough(page) && rows_.back() < max_rows_) grow_last_page();
  }
  if (page == free_.size() || !enough(page)) {
    add_page();
    page = pages_.size() - 1;
  }
  for (int b = 0; b < count; ++b) {
    out[b] = {static_cast<int>(page), free_[page].back()};
    free_[page].pop_back();
  }
}

void ShadowCache::copy_block(glm::ivec2 from, Block to) {
  const GladGLContext& api = *api_;
  const glm::ivec2 o = origin(to.index);
  api.BindFramebuffer(GL_DRAW_FRAMEBUFFER, page_fbos_[static_cast<std::size_t>(to.page)].get());
  api.BlitFramebuffer(from.x, from.y, from.x + block_.x, from.y + block_.y, o.x, o.y,
                      o.x + block_.x, o.y + block_.y, GL_DEPTH_BUFFER_BIT | GL_COLOR_BUFFER_BIT,
                      GL_NEAREST);
}

void ShadowCache::store(std::uint32_t slot, const std::vector<Vpl>& vpls, const GpuScene& gpu,
                        const std::vector<VplLobe>& lobes) {
  if (slot >= slots_.size()) slots_.resize(std::size_t(slot) + 1);
  std::vector<Kept>& kept = slots_[slot];
  for (const Kept& k : kept)
    for (int b = 0; b < k.count; ++b)
      free_[static_cast<std::size_t>(k.blocks[b].page)].push_back(k.blocks[b].index);
  kept.clear();
  std::vector<const Vpl*> batch;
  std::vector<glm::mat3> frames;
  std::vector<float> fars;
  std::vector<glm::ivec4> blocks;
  const auto flush = [&] {
    if (batch.empty()) return;
    atlas_.render(batch.data(), static_cast<int>(batch.size()), gpu, frames, fars, blocks);
    for (std::size_t s = 0; s < batch.size(); ++s) {
      Kept k{*batch[s], frames[s], fars[s], {}, ShadowAtlas::blocks_for(*batch[s]), {}};
      if (const VplLobe* lobe = find_lobe(lobes, *batch[s])) k.lobe = *lobe;
      allocate(k.count, k.blocks); // may bind a new page's framebuffer
      api_->Disable(GL_SCISSOR_TEST);
      api_->BindFramebuffer(GL_READ_FRAMEBUFFER, read_fbo_.get());
      api_->FramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D,
                                 atlas_.texture(), 0);
      api_->FramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D,
                                 atlas_.gradient_texture(), 0);
      api_->ReadBuffer(GL_COLOR_ATTACHMENT0);
      copy_block({blocks[s].x, blocks[s].y}, k.blocks[0]);
      if (k.count == 2) copy_block({blocks[s].z, blocks[s].w}, k.blocks[1]);
      kept.push_back(k);
    }
    batch.clear();
  };
  std::vector<const Vpl*> all;
  for (const Vpl& v : vpls) all.push_back(&v);
  int blocks_used = 0;
  for (const Vpl* v : ShadowAtlas::batch_order(std::move(all))) {
    const int need = ShadowAtlas::blocks_for(*v);
    if (static_cast<int>(batch.size()) == atlas_.batch() || blocks_used + need > atlas_.blocks() ||
        (!batch.empty() && !ShadowAtlas::same_batch(*batch.back(), *v))) {
      flush();
      blocks_used = 0;
    }
    batch.push_back(v);
    blocks_used += need;
  }
  flush();
}

std::vector<ShadowCache::Page> ShadowCache::pages() const {
  std::vector<Page> out(pages_.size());
  for (std::size_t p = 0; p < pages_.size(); ++p) {
    out[p].lookup = {pages_[p].get(), resolution_};
    out[p].lookup.gradient = gradients_[p].get();
  }
  for (const std::vector<Kept>& slot : slots_)
    for (const Kept& k : slot) {
      const glm::ivec2 b0 = origin(k.blocks[0].index);
      const glm::ivec2 b1 = k.count == 2 ? origin(k.blocks[1].index) : b0;
      AtlasVpl a{&k.vpl, k.frame, k.far, glm::ivec4(b0, b1), 0};
      a.lobe = k.lobe ? &*k.lobe : nullptr;
      out[static_cast<std::size_t>(k.blocks[0].page)].vpls.push_back(a);
    }
  return out;
}

std::size_t ShadowCache::bytes() const {
  std::size_t texels = 0;
  for (int rows : rows_)
    texels +=
        static_cast<std::size_t>(columns_ * block_.x) * static_cast<std::size_t>(rows * block_.y);
  return texels * sizeof(float);
}

} // namespace irad::gl
