#include "raster/shadow/shadow_atlas.h"

#include "core/scene/mirrors.h"
#include "core/util/error.h"
#include "raster/glsl/batched_shaders.h"
#include "raster/shadow/shadow_cube.h"
#include "raster/shadow/shadow_occlusion.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

namespace irad::gl {

namespace {

constexpr GLuint kShadowBlockBinding = 0;

// Blocks per row and rows for `blocks` blocks of size `block`, about as wide as high.
glm::ivec2 block_grid(int blocks, glm::ivec2 block) {
  const double ratio = static_cast<double>(block.y) / block.x;
  const int columns = std::max(1, static_cast<int>(std::lround(std::sqrt(blocks * ratio))));
  const int rows = (blocks + columns - 1) / columns;
  return {(blocks + rows - 1) / rows, rows};
}

// Floats of the ShadowBatch block (std140: mat4 and vec4 arrays are tightly packed).
std::size_t block_floats(int batch) {
  return static_cast<std::size_t>(batch) * shaders::kShadowBytesPerVpl / sizeof(float);
}

// Face f's window rectangle that is ever looked up (x0, y0, x1, y1; x0 > x1: none) and its
// offset atlas texel - face texel, for a VPL whose blocks start at b0 and b1.
void face_placement(const CubeFaces& cube, int f, int r, glm::ivec2 b0, glm::ivec2 b1,
                    glm::vec4& rect, glm::vec2& offset) {
  const float rf = static_cast<float>(r);
  rect = {0.0f, 0.0f, rf, rf};
  if (!cube.hemisphere) {
    offset = glm::vec2(f < 3 ? b0 : b1) + glm::vec2(static_cast<float>((f % 3) * r), 0.0f);
    return;
  }
  const int h = r / 2 + 1;
  const glm::ivec2 within[6] = {{r, 0}, {2 * h, 0}, {r + 2 * h, h - r}, {r + 2 * h, h}, {0, 0}, {}};
  offset = glm::vec2(b0 + within[f]);
  if (f == kNegativeZFace) {
    rect = {1.0f, 1.0f, -1.0f, -1.0f};
  } else if (f < 4) {
    const glm::vec4 w(front_half(f, r));
    rect = {w.x, w.y, w.x + w.z, w.y + w.w};
  }
}

} // namespace

int max_atlas_side(const GladGLContext& api) {
  GLint texture = 0, renderbuffer = 0;
  api.GetIntegerv(GL_MAX_TEXTURE_SIZE, &texture);
  api.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &renderbuffer);
  return std::min({kMaxAtlasSide, int(texture), int(renderbuffer)});
}

int ShadowAtlas::capacity(const GladGLContext& api, int resolution, int wanted) {
  GLint uniform_block = 0;
  api.GetIntegerv(GL_MAX_UNIFORM_BLOCK_SIZE, &uniform_block);
  const int side = max_atlas_side(api);
  const glm::ivec2 block = ShadowAtlas::block_size(resolution);
  int b = std::min(wanted, static_cast<int>(uniform_block) / shaders::kShadowBytesPerVpl);
  for (; b > 1; --b) {
    const glm::ivec2 size = block_grid(b, block) * block;
    if (size.x <= side && size.y <= side) break;
  }
  return std::max(b, 0);
}

ShadowAtlas::ShadowAtlas(const GladGLContext& api, int resolution, int batch, int blocks,
                         const Bounds& bounds, const MaterialFeatures& features,
                         const ShadowLodOptions& lod, LodProvider* shared, int slots)
    : api_(&api), resolution_(resolution), batch_(batch),
      block_(ShadowAtlas::block_size(resolution)), grid_(block_grid(blocks, block_)),
      bounds_(bounds),
      program_(
          api, "batched shadow",
          material_source(shaders::batched_source(shaders::batched_shadow_vertex, batch), features),
          material_source(shaders::batched_source(shaders::batched_shadow_fragment, batch),
                          features)),
      material_(program_), block_buffer_(make_buffer(api)), block_data_(block_floats(batch), 0.0f),
      lod_options_(lod), u_face_(program_.uniform("u_face")),
      u_copies_(features.mirrors ? program_.uniform("u_copies") : -1), shared_lod_(shared) {
  const glm::ivec2 size = grid_ * block_;
  GLint uniform_block = 0;
  api.GetIntegerv(GL_MAX_UNIFORM_BLOCK_SIZE, &uniform_block);
  if (batch < 1 || blocks < 2 || std::max(size.x, size.y) > max_atlas_side(api) ||
      batch * shaders::kShadowBytesPerVpl > uniform_block)
    throw Error("", "shadow atlas",
                "a batch of " + std::to_string(batch) + " VPLs with " + std::to_string(resolution) +
                    "^2 faces does not fit this OpenGL");
  const auto n = static_cast<std::size_t>(std::max(slots, 2));
  atlas_.resize(n);
  gradient_.resize(n);
  fbo_.resize(n);
  for (std::size_t a = 0; a < n; ++a) {
    atlas_[a] = make_depth_texture(api, size.x, size.y);
    fbo_[a] = make_depth_framebuffer(api, atlas_[a].get(), "shadow atlas framebuffer");
    if (lod.planes != ShadowPlanes::Off) add_gradient(a); // else depth only
  }
  const GLuint index = api.GetUniformBlockIndex(program_.get(), "ShadowBatch");
  if (index == GL_INVALID_INDEX) throw Error("", "shader batched shadow", "no block ShadowBatch");
  api.UniformBlockBinding(program_.get(), index, kShadowBlockBinding);
  program_.use();
  api.Uniform1f(program_.uniform("u_face_size"), static_cast<float>(resolution));
  api.Uniform2f(program_.uniform("u_atlas_size"), static_cast<float>(size.x),
                static_cast<float>(size.y));
  api.Uniform1i(u_face_, -1); // the face from gl_InstanceID
  if (features.mirrors) {     // ShadowCube::render_mirrored's clip plane
    api.Uniform1i(u_copies_, 1);
    api.Uniform1f(program_.uniform("u_mirror_clip"), 1e-5f * bounds.diagonal());
  }
}

void ShadowAtlas::add_gradient(std::size_t a) {
  const GladGLContext& api = *api_;
  const glm::ivec2 size = grid_ * block_;
  gradient_[a] = make_gradient_texture(api, size.x, size.y);
  api.BindFramebuffer(GL_FRAMEBUFFER, fbo_[a].get());
  api.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, gradient_[a].get(),
                           0);
  api.DrawBuffer(GL_COLOR_ATTACHMENT0);
  check_framebuffer(api, "shadow atlas framebuffer");
}

void ShadowAtlas::enable_planes() {
  if (lod_options_.planes != ShadowPlanes::Off) return;
  lod_options_.planes = ShadowPlanes::On;
  if (fbo_.empty()) { // released: what a shading pass binds
    gradient_[0] = make_gradient_texture(*api_, 1, 1);
    return;
  }
  for (std::size_t a = 0; a < fbo_.size(); ++a) add_gradient(a);
}

void ShadowAtlas::release_atlases() {
  const GladGLContext& api = *api_;
  atlas_.resize(1);
  gradient_.resize(1);
  fbo_.clear();
  current_ = 0;
  atlas_[0] = make_depth_texture(api, 1, 1);
  gradient_[0] =
      lod_options_.planes != ShadowPlanes::Off ? make_gradient_texture(api, 1, 1) : Texture();
}

bool ShadowAtlas::prepare_lod(const GpuScene& scene) {
  if (lod_options_.mode == ShadowLodMode::Off || scene.scene().animation) return false;
  if (!lod_) {
    if (!shared_lod_) {
      own_lod_ = std::make_unique<LodProvider>(*api_, scene, lod_options_);
      shared_lod_ = own_lod_.get();
    }
    lod_ = shared_lod_->get();
    if (lod_) lod_vao_ = lod_->vertex_array(); // in this atlas's context
  }
  return lod_ && !lod_->clusters().nodes.empty();
}

void ShadowAtlas::draw_clusters(int n, const GpuScene& scene) {
  const GladGLContext& api = *api_;
  if (scene.features().alpha) { // not in the hierarchy: every face, through gl_InstanceID
    scene.draw_if([](const Material& m) { return m.alpha_mode != AlphaMode::Opaque; },
                  [&](const Material& m) { material_.bind_alpha(api, scene, m); }, 6 * n,
                  &scene_vao_);
    material_.bind_alpha(api, scene, Material{}); // opaque: nothing absent
  }
  pick_faces();
  std::size_t picked = 0;
  for (std::size_t t : totals_) picked += t / 3;
  if (lod_options_.occlusion && picked >= kOcclusionTrianglesPerVpl * static_cast<std::size_t>(n))
    draw_in_rounds();
  else
    draw_faces(picks_);
  api.Uniform1i(u_face_, -1);
}

void ShadowAtlas::pick_faces() {
  const float per_distance = lod_options_.texels * texel_angle();
  // A twentieth of the shading passes' constant depth bias (2e-4 of the diagonal).
  const float floor = 1e-5f * bounds_.diagonal();
  picks_.resize(faces_.size());
  totals_.assign(faces_.size(), 0);
  // Faces picked again, where a pick wanted deferred levels, once those are built.
  std::vector<std::size_t> faces;
  for (std::size_t i = 0; i < faces_.size(); ++i)
    if (faces_[i].rect.x <= faces_[i].rect.z) faces.push_back(i); // else never looked up
  for (std::size_t i = 0; i < faces_.size(); ++i) picks_[i].clear();
  while (!faces.empty()) {
    wanted_.clear();
    std::vector<std::size_t> again;
    for (std::size_t i : faces) {
      const Face& f = faces_[i];
      const std::size_t before = wanted_.size();
      picks_[i].clear();
      lod_->pick(face_planes(f.view_projection, f.rect, resolution_), f.origin, per_distance, floor,
                 plans_, picks_[i], &wanted_);
      if (wanted_.size() > before) again.push_back(i);
    }
    if (!wanted_.empty()) lod_->build_levels(wanted_);
    faces = std::move(again);
  }
  for (std::size_t i = 0; i < faces_.size(); ++i)
    for (const ClusterPick& p : picks_[i]) totals_[i] += p.count;
}

void ShadowAtlas::draw_in_rounds() {
  near_.resize(faces_.size());
  taken_.assign(faces_.size(), 0);
  for (std::size_t i = 0; i < faces_.size(); ++i) sort_by_distance(faces_[i], picks_[i]);
  for (std::size_t r = 0; r < kRounds.size(); ++r) {
    for (std::size_t i = 0; i < faces_.size(); ++i)
      take_nearest(i, r + 1 == kRounds.size() ? 2.0 : kRounds[r], near_[i]);
    const bool any = std::any_of(near_.begin(), near_.end(),
                                 [](const std::vector<ClusterPick>& p) { return !p.empty(); });
    if (!any) continue;
    if (r > 0) cull_occluded(near_); // against the depths of the rounds before
    draw_faces(near_);
  }
}

void ShadowAtlas::sort_by_distance(const Face& f, std::vector<ClusterPick>& picks) const {
  std::vector<std::pair<float, ClusterPick>> keyed;
  keyed.reserve(picks.size());
  for (const ClusterPick& p : picks)
    keyed.emplace_back(
        distance_to(lod_->clusters().nodes[static_cast<std::size_t>(p.node)].bounds, f.origin), p);
  std::stable_sort(keyed.begin(), keyed.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  for (std::size_t i = 0; i < picks.size(); ++i) picks[i] = keyed[i].second;
}

void ShadowAtlas::take_nearest(std::size_t face, double share, std::vector<ClusterPick>& out) {
  std::vector<ClusterPick>& picks = picks_[face];
  out.clear();
  const double target = share * static_cast<double>(totals_[face]);
  // Whole picks up to the share (one that would pass it waits for a round with the depths of
  // those before it: a large far mesh is what occlusion culling is for), but at least one.
  std::size_t taken = 0;
  while (taken < picks.size() &&
         (taken_[face] == 0 || static_cast<double>(taken_[face] + picks[taken].count) <= target))
    taken_[face] += picks[taken++].count;
  out.assign(picks.begin(), picks.begin() + static_cast<std::ptrdiff_t>(taken));
  picks.erase(picks.begin(), picks.begin() + static_cast<std::ptrdiff_t>(taken));
}

void ShadowAtlas::cull_occluded(std::vector<std::vector<ClusterPick>>& per_face) {
  const GladGLContext& api = *api_;
  int rows = 0; // the atlas rows the faces use
  for (const Face& f : faces_)
    if (f.rect.x <= f.rect.z) rows = std::max(rows, f.offset.y + static_cast<int>(f.rect.w));
  const glm::ivec2 size = grid_ * block_;
  depth_.resize(static_cast<std::size_t>(size.x) * static_cast<std::size_t>(rows));
  api.PixelStorei(GL_PACK_ALIGNMENT, 4);
  api.ReadPixels(0, 0, size.x, rows, GL_DEPTH_COMPONENT, GL_FLOAT, depth_.data());
  for (std::size_t i = 0; i < faces_.size(); ++i) {
    const Face& f = faces_[i];
    if (per_face[i].empty()) continue;
    const FaceDepthBound bound(depth_.data(), size, f.offset, glm::ivec4(f.rect), resolution_);
    std::erase_if(per_face[i], [&](const ClusterPick& p) {
      return !bound.may_show(lod_->clusters().nodes[static_cast<std::size_t>(p.node)].bounds,
                             f.view_projection, resolution_, f.origin, f.inv_far);
    });
  }
}

void ShadowAtlas::draw_faces(std::vector<std::vector<ClusterPick>>& per_face) {
  lod_->make_resident(per_face);
  for (std::size_t i = 0; i < faces_.size(); ++i) {
    std::vector<ClusterPick>& picks = per_face[i];
    if (picks.empty()) continue;
    // In the hierarchy's order, so that ranges that touch (there, and in the slabs where their
    // pages were copied together) become one.
    std::sort(picks.begin(), picks.end(),
              [](const ClusterPick& a, const ClusterPick& b) { return a.first < b.first; });
    lod_->select(picks, selection_);
    cluster_triangles_ += selection_.triangles;
    api_->Uniform1i(u_face_, faces_[i].instance);
    lod_->draw(selection_, lod_vao_);
    unflushed_ += selection_.triangles;
    if (unflushed_ >= kFlushTriangles) {
      api_->Flush();
      unflushed_ = 0;
    }
  }
}

void ShadowAtlas::render(const Vpl* const* vpls, int n, const GpuScene& scene,
                         std::vector<glm::mat3>& frames, std::vector<float>& fars,
                         std::vector<glm::ivec4>& blocks) {
  const GladGLContext& api = *api_;
  if (fbo_.empty()) throw Error("", "shadow atlas", "drawn into after its atlases were released");
  if (!scene_vao_) scene_vao_ = scene.vertex_array(); // in this atlas's context
  cluster_triangles_ = 0;
  unflushed_ = 0; // the framebuffer bind below ends the GL's scene
  frames.resize(static_cast<std::size_t>(n));
  fars.resize(static_cast<std::size_t>(n));
  blocks.resize(static_cast<std::size_t>(n));
  // The block: face matrices, rectangles, offsets, positions (std140 offsets).
  float* matrices = block_data_.data();
  float* rects = matrices + 6 * 16 * batch_;
  float* offsets = rects + 6 * 4 * batch_;
  float* origins = offsets + 6 * 4 * batch_;
  float* mirrors = origins + 4 * batch_;
  int next_block = 0;
  int copies = 1; // 2: some VPL is mirrored (raster/glsl/batched_shaders.h)
  faces_.clear();
  for (int s = 0; s < n; ++s) {
    const Vpl& vpl = *vpls[s];
    float far = far_from(bounds_, vpl.position);
    glm::vec4 mirror(0.0f);
    if (vpl.mirror >= 0) { // the reflected scene is as far from y' as the real one from y
      mirror = vpl.mirror_plane;
      far = std::max(far, far_from(bounds_, reflect_point(mirror, vpl.position)));
      copies = 2;
    }
    std::memcpy(mirrors + 4 * s, &mirror[0], 4 * sizeof(float));
    const CubeFaces cube = cube_faces(vpl, bounds_, far);
    const glm::ivec2 b0 = block_origin(next_block);
    const glm::ivec2 b1 = cube.hemisphere ? b0 : block_origin(next_block + 1);
    next_block += cube.hemisphere ? 1 : 2;
    if (next_block > this->blocks()) throw Error("", "shadow atlas", "batch exceeds the blocks");
    frames[static_cast<std::size_t>(s)] = cube.frame;
    fars[static_cast<std::size_t>(s)] = cube.far;
    blocks[static_cast<std::size_t>(s)] = glm::ivec4(b0, b1);
    std::memcpy(origins + 4 * s, &vpl.position[0], 3 * sizeof(float));
    origins[4 * s + 3] = 1.0f / cube.far;
    for (int f = 0; f < 6; ++f) {
      const int i = 6 * s + f;
      glm::vec4 rect;
      glm::vec2 offset;
      face_placement(cube, f, resolution_, b0, b1, rect, offset);
      std::memcpy(matrices + 16 * i, &cube.view_projection[f][0][0], 16 * sizeof(float));
      std::memcpy(rects + 4 * i, &rect[0], 4 * sizeof(float));
      std::memcpy(offsets + 4 * i, &offset[0], 2 * sizeof(float));
      faces_.push_back(
          {i, cube.view_projection[f], rect, vpl.position, glm::ivec2(offset), 1.0f / cube.far});
    }
  }
  // A new store per batch (no wait for the draw that read the last one).
  api.BindBuffer(GL_UNIFORM_BUFFER, block_buffer_.get());
  api.BufferData(GL_UNIFORM_BUFFER, static_cast<GLsizeiptr>(block_data_.size() * sizeof(float)),
                 block_data_.data(), GL_STREAM_DRAW);
  api.BindBufferBase(GL_UNIFORM_BUFFER, kShadowBlockBinding, block_buffer_.get());

  current_ = (current_ + 1) % atlas_.size();
  api.BindFramebuffer(GL_FRAMEBUFFER, fbo_[current_].get());
  const glm::ivec2 size = grid_ * block_;
  api.Viewport(0, 0, size.x, size.y);
  api.Disable(GL_SCISSOR_TEST);
  api.Enable(GL_DEPTH_TEST);
  api.DepthFunc(GL_LESS);
  api.DepthMask(GL_TRUE);
  api.Disable(GL_BLEND);
  api.ClearDepth(1.0);                    // far: nothing there, never shadowed
  api.ClearColor(0.0f, 0.0f, 0.0f, 0.0f); // no slope
  api.Clear(GL_DEPTH_BUFFER_BIT | (gradient_[current_] ? GL_COLOR_BUFFER_BIT : 0));
  program_.use();
  const int clip_planes = u_copies_ >= 0 ? 5 : 4;
  for (int k = 0; k < clip_planes; ++k) api.Enable(static_cast<GLenum>(GL_CLIP_DISTANCE0 + k));
  if (u_copies_ >= 0) api.Uniform1i(u_copies_, copies);
  // The hierarchy culls against the faces' frusta, not the reflected scene's: a batch with
  // mirrored VPLs draws everything.
  if (copies == 1 && prepare_lod(scene))
    draw_clusters(n, scene);
  else
    scene.draw_covered(
        6 * copies * n, [&](const Material& m) { material_.bind_alpha(api, scene, m); },
        &scene_vao_);
  for (int k = 0; k < clip_planes; ++k) api.Disable(static_cast<GLenum>(GL_CLIP_DISTANCE0 + k));
}

} // namespace irad::gl
