#include "raster/shadow/shadow_lod.h"

#include "core/mesh/hierarchy/cluster_levels.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace irad::gl {

namespace {

// The largest and smallest of a * p + d over the box b.
glm::vec2 plane_range(const glm::vec4& plane, const Bounds& b) {
  const glm::vec3 a(plane);
  const glm::vec3 centre = b.center(), half = 0.5f * (b.hi - b.lo);
  const float mid = glm::dot(a, centre) + plane.w;
  const float reach = glm::dot(glm::abs(a), half);
  return {mid - reach, mid + reach};
}

} // namespace

void add_range(std::size_t first, std::size_t count, ClusterSelection::Slab& out) {
  if (count == 0) return;
  // Byte offsets into the index buffer, as glMultiDrawElements takes them (pointers that are no
  // address: their arithmetic is done on integers).
  const std::uintptr_t offset = std::uintptr_t(first) * sizeof(std::uint32_t);
  const auto end_of_last = [&] {
    return reinterpret_cast<std::uintptr_t>(out.offsets.back()) +
           std::uintptr_t(out.counts.back()) * sizeof(std::uint32_t);
  };
  if (!out.counts.empty() && end_of_last() == offset) {
    out.counts.back() += static_cast<GLsizei>(count);
    return;
  }
  out.counts.push_back(static_cast<GLsizei>(count));
  out.offsets.push_back(reinterpret_cast<const void*>(offset));
}

std::array<glm::vec4, 4> face_planes(const glm::mat4& view_projection, const glm::vec4& rect,
                                     int resolution) {
  // Clip c = M p (rows of M), face pixel times w: pw = (c.xy + c.w) R / 2; inside where
  // x0 w <= pw.x <= x1 w and y0 w <= pw.y <= y1 w (w = c.w > 0 in front of the VPL).
  const glm::mat4 t = glm::transpose(view_projection); // t[i]: row i of M
  const float h = 0.5f * static_cast<float>(resolution);
  const glm::vec4 px = h * (t[0] + t[3]), py = h * (t[1] + t[3]), w = t[3];
  return {px - rect.x * w, rect.z * w - px, py - rect.y * w, rect.w * w - py};
}

ShadowLod::ShadowLod(const GladGLContext& api, const GpuScene& gpu, MeshClusters clusters,
                     bool simplify, std::size_t slab_pages)
    : api_(&api), gpu_(&gpu), clusters_(std::move(clusters)), simplify_(simplify),
      slab_pages_(std::max<std::size_t>(slab_pages, 1)) {
  index_count_ = clusters_.index_count();
  std::vector<std::uint32_t>().swap(clusters_.triangles); // what the cache keeps, not the faces
  if (!clusters_.stored_indices) // the pages' one source: a build's indices, moved behind it
    clusters_.stored_indices = std::make_shared<const StoredIndices>(
        std::make_shared<const std::vector<std::uint32_t>>(std::move(clusters_.indices)));
  clusters_.indices = {};
  slot_of_page_.assign((clusters_.index_end() + kPageIndices - 1) / kPageIndices, 0);
}

static_assert(kLateAlign % ShadowLod::kPageIndices == 0, "late indices start on a page");

void ShadowLod::build_levels(const std::vector<std::int32_t>& nodes) const {
  const std::unique_lock lock(levels_mutex_);
  const auto start = std::chrono::steady_clock::now();
  const std::size_t before = clusters_.late_nodes.size();
  add_deferred_levels(gpu_->scene(), clusters_, nodes, 0);
  late_.nodes += clusters_.late_nodes.size() - before;
  late_.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::lock_guard pages(pages_mutex_);
  slot_of_page_.resize((clusters_.index_end() + kPageIndices - 1) / kPageIndices, 0);
}

ShadowLod::LateLevels ShadowLod::late_levels() const {
  const std::shared_lock lock(levels_mutex_);
  return late_;
}

GLuint ShadowLod::slab_of(std::size_t slot) const {
  const std::size_t slab = slot / slab_pages_;
  // The slots fill in order. A slab holds at most the pages not yet copied (the pages of levels
  // built later start a slab of their own once it is full). A slab is written page by page over
  // the render (dynamic use: Mesa warns of every mapped write into a static buffer).
  if (slab == slabs_.size()) {
    const std::size_t pages = std::min(slab_pages_, slot_of_page_.size() - pages_copied_);
    slabs_.push_back(make_buffer(*api_));
    slab_capacity_.push_back(pages);
    api_->BindBuffer(GL_COPY_WRITE_BUFFER, slabs_.back().get());
    api_->BufferData(GL_COPY_WRITE_BUFFER,
                     static_cast<GLsizeiptr>(pages * kPageIndices * sizeof(std::uint32_t)), nullptr,
                     GL_DYNAMIC_DRAW);
    api_->BindBuffer(GL_COPY_WRITE_BUFFER, 0);
  }
  return slabs_[slab].get();
}

std::size_t ShadowLod::free_slots() const {
  const std::size_t in_slab = slots_used_ % slab_pages_;
  if (in_slab != 0 && in_slab >= slab_capacity_.back()) // a full slab made smaller: the next
    slots_used_ += slab_pages_ - in_slab;
  const std::size_t slab = slots_used_ / slab_pages_;
  return slab < slabs_.size() ? slab_capacity_[slab] - slots_used_ % slab_pages_
                              : std::min(slab_pages_, slot_of_page_.size() - pages_copied_);
}

void ShadowLod::copy_pages(std::size_t page, std::size_t slot, std::size_t count) const {
  const std::size_t first = page * kPageIndices;
  const bool late = page >= late_page();
  const std::size_t end = late ? clusters_.index_end() : index_count_;
  const std::size_t indices = std::min((page + count) * kPageIndices, end) - first;
  fill_buffer_range(
      *api_, slab_of(slot), (slot % slab_pages_) * kPageIndices * sizeof(std::uint32_t),
      indices * sizeof(std::uint32_t),
      [&](void* storage) {
        auto* out = static_cast<std::uint32_t*>(storage);
        if (late)
          std::copy_n(clusters_.late_indices.begin() +
                          static_cast<std::ptrdiff_t>(first - clusters_.late_base()),
                      indices, out);
        else
          clusters_.stored_indices->copy_range(first, indices, out);
      },
      "cluster hierarchy");
}

void ShadowLod::make_resident(const std::vector<std::vector<ClusterPick>>& picks) const {
  const std::shared_lock levels(levels_mutex_); // the late indices stay put
  const std::lock_guard lock(pages_mutex_);
  std::vector<std::size_t> missing;
  for (const std::vector<ClusterPick>& face : picks)
    for (const ClusterPick& p : face) {
      if (p.count == 0) continue;
      const std::size_t last = (std::size_t{p.first} + p.count - 1) / kPageIndices;
      for (std::size_t page = p.first / kPageIndices; page <= last; ++page)
        if (slot_of_page_[page] == 0) missing.push_back(page);
    }
  if (missing.empty()) return;
  std::sort(missing.begin(), missing.end());
  missing.erase(std::unique(missing.begin(), missing.end()), missing.end());
  for (std::size_t i = 0; i < missing.size();) {
    // A run of consecutive pages into consecutive slots of one slab: one read, one mapping.
    // (Marked placed once copied: a copy that throws leaves its pages absent.)
    const std::size_t room = free_slots(), slot = slots_used_;
    std::size_t j = i + 1;
    while (j < missing.size() && missing[j] == missing[j - 1] + 1 && j - i < room &&
           missing[j] != late_page())
      ++j;
    copy_pages(missing[i], slot, j - i);
    for (std::size_t k = i; k < j; ++k)
      slot_of_page_[missing[k]] = static_cast<std::uint32_t>(slot + (k - i) + 1);
    slots_used_ += j - i;
    pages_copied_ += j - i;
    i = j;
  }
  if (shared_) api_->Finish();
}

void ShadowLod::share_with_contexts() const {
  const std::lock_guard lock(pages_mutex_);
  shared_ = true;
  api_->Finish();
}

void ShadowLod::select(const std::vector<ClusterPick>& picks, ClusterSelection& out) const {
  const std::lock_guard lock(pages_mutex_);
  out.clear();
  if (out.slabs.size() < slabs_.size()) out.slabs.resize(slabs_.size());
  for (std::size_t s = 0; s < slabs_.size(); ++s) out.slabs[s].buffer = slabs_[s].get();
  for (const ClusterPick& p : picks) {
    out.triangles += p.count / 3;
    // Page by page (a page's indices lie together in its slot).
    for (std::size_t at = p.first, end = std::size_t{p.first} + p.count; at < end;) {
      const std::size_t page = at / kPageIndices;
      const std::size_t until = std::min(end, (page + 1) * kPageIndices);
      const std::size_t slot = slot_of_page_[page] - 1;
      add_range((slot % slab_pages_) * kPageIndices + at % kPageIndices, until - at,
                out.slabs[slot / slab_pages_]);
      at = until;
    }
  }
}

std::size_t ShadowLod::gpu_bytes() const {
  const std::lock_guard lock(pages_mutex_);
  std::size_t pages = 0;
  for (std::size_t p : slab_capacity_) pages += p;
  return pages * kPageIndices * sizeof(std::uint32_t);
}

// Per node visited: what it draws (a mesh range, its children, or nothing) and how many
// triangles that is; the cheapest of its acceptable meshes and its children's plans.
std::uint32_t ShadowLod::plan(std::int32_t id, const Query& q) const {
  const ClusterNode& node = clusters_.nodes[static_cast<std::size_t>(id)];
  Choice& c = (*q.plans)[static_cast<std::size_t>(id)];
  bool inside = true, outside = false;
  for (const glm::vec4& p : *q.planes) {
    const glm::vec2 r = plane_range(p, node.bounds);
    // A margin of float rounding (relative to the terms): culling only what is surely out.
    const float margin =
        1e-5f * (std::abs(p.w) + glm::dot(glm::abs(glm::vec3(p)),
                                          glm::abs(node.bounds.hi) + glm::abs(node.bounds.lo)));
    if (r.y < -margin) outside = true;
    if (r.x < margin) inside = false;
  }
  c = {0, 0, false};
  if (outside) return 0;
  // The original triangles below: always right.
  c.first = node.leaf_first;
  c.count = node.leaf_count;
  if (!simplify_) {
    if (node.leaf() || inside) return c.count;
  } else {
    const float allowed =
        std::max(q.error_floor, q.error_per_distance * distance_to(node.bounds, q.origin));
    if (node.error <= allowed && node.mesh_count < c.count) {
      c.first = node.mesh_first;
      c.count = node.mesh_count;
    }
    // Its levels could be drawn (their errors are at least the mesh's): wanted first.
    if (node.levels_pending() && node.error <= allowed && q.wanted) {
      q.wanted->push_back(id);
      return c.count;
    }
    for (std::uint32_t l = 0; l < node.levels_count; ++l) {
      const ClusterLevel& level = clusters_.levels[node.levels_first + l];
      if (level.error <= allowed && level.count < c.count) {
        c.first = level.first;
        c.count = level.count;
      }
    }
    // A leaf, or a mesh too small for its children to do much better.
    if (node.leaf() || c.count <= 3 * kSmallEnough) return c.count;
  }
  // (c stays valid: the plans are not resized while planning.)
  const std::uint32_t below = plan(node.children[0], q) + plan(node.children[1], q);
  if (below < c.count) {
    c.children = true;
    c.count = below;
  }
  return c.count;
}

void ShadowLod::emit_plan(std::int32_t id, const Plans& plans,
                          std::vector<ClusterPick>& out) const {
  const Choice& c = plans[static_cast<std::size_t>(id)];
  if (c.count == 0) return;
  const ClusterNode& node = clusters_.nodes[static_cast<std::size_t>(id)];
  if (!c.children) {
    out.push_back({c.first, c.count, id});
    return;
  }
  emit_plan(node.children[0], plans, out);
  emit_plan(node.children[1], plans, out);
}

void ShadowLod::pick(std::span<const std::int32_t> roots, const std::array<glm::vec4, 4>& planes,
                     const glm::vec3& origin, float error_per_distance, float error_floor,
                     Plans& plans, std::vector<ClusterPick>& out,
                     std::vector<std::int32_t>* wanted) const {
  const std::shared_lock lock(levels_mutex_);
  plans.resize(clusters_.nodes.size());
  const Query q{&planes, origin, error_per_distance, error_floor, &plans, wanted};
  for (std::int32_t root : roots) {
    plan(root, q);
    emit_plan(root, plans, out);
  }
}

void ShadowLod::draw(const ClusterSelection& selection, const VertexArray& vao) const {
  api_->BindVertexArray(vao.get());
  for (const ClusterSelection::Slab& slab : selection.slabs) {
    if (slab.counts.empty()) continue;
    // Bound again for every draw: pages another context wrote are then visible in this one.
    api_->BindBuffer(GL_ELEMENT_ARRAY_BUFFER, slab.buffer);
    api_->MultiDrawElements(GL_TRIANGLES, slab.counts.data(), GL_UNSIGNED_INT, slab.offsets.data(),
                            static_cast<GLsizei>(slab.counts.size()));
  }
}

} // namespace irad::gl
