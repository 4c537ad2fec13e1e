#include "walk/rays/ray_scene.h"

#include "core/animation/animation.h"
#include "core/sampling/rng.h"
#include "core/util/error.h"
#include "walk/rays/alpha.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <vector>

#include <cmath>
#include <embree3/rtcore.h>
#include <limits>
#include <string>

namespace irad {

namespace {

// Collects the first Embree error; checked after every call that can fail.
struct ErrorSink {
  std::string message;
};

void on_embree_error(void* user, RTCError code, const char* str) {
  auto* sink = static_cast<ErrorSink*>(user);
  if (sink->message.empty())
    sink->message = "Embree error " + std::to_string(static_cast<int>(code)) + ": " +
                    (str ? str : "(no message)");
}

// One Embree triangle geometry over a subset of the scene's triangles.
struct GeometryPart {
  unsigned id = RTC_INVALID_GEOMETRY_ID;
  std::vector<std::uint32_t> triangles; // Embree primID -> scene triangle
  std::vector<std::uint32_t> vertices;  // Embree vertex -> scene vertex
  RTCGeometry geometry = nullptr;       // owned by the scene once attached
  float* vertex_buffer = nullptr;
  const Scene* alpha_scene = nullptr; // the filters' scene (walk/rays/alpha.h); null: no filter

  std::uint32_t scene_triangle(unsigned prim) const {
    return triangles.empty() ? prim : triangles[prim];
  }
};

// Embree 3's query context with the caller's salt: Embree hands the filter the context pointer it
// was given, so the filter reads the salt back (base must stay the first member).
struct SaltedContext {
  RTCIntersectContext base;
  std::uint64_t salt = 0;
  explicit SaltedContext(std::uint64_t s) : salt(s) { rtcInitIntersectContext(&base); }
};

// The context of intersect_leaving: per lane of the packet, the scene triangle its ray passes
// through (salted first, so the alpha filter reads its salt as from a SaltedContext).
struct LeavingContext {
  SaltedContext salted;
  const GeometryPart* parts[2] = {nullptr, nullptr};
  const std::uint32_t* leave = nullptr; // of the packet's first lane
  explicit LeavingContext(std::uint64_t salt) : salted(salt) {}
};

// Context filter of intersect_leaving: refuses a lane's hit on its own triangle.
void leaving_filter(const RTCFilterFunctionNArguments* args) {
  const auto* context = reinterpret_cast<const LeavingContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const unsigned geom = RTCHitN_geomID(args->hit, args->N, i);
    const GeometryPart* part = context->parts[context->parts[1] && context->parts[1]->id == geom];
    if (part->scene_triangle(RTCHitN_primID(args->hit, args->N, i)) == context->leave[i])
      args->valid[i] = 0;
  }
}

// Uniform in [0, 1) from the ray (origin and direction bits), the salt and the scene triangle.
double hit_random(std::uint64_t salt, const float (&ray)[6], std::uint32_t triangle) {
  std::uint64_t h = mix64(salt);
  for (int i = 0; i < 6; i += 2)
    h = mix64(h ^ (std::uint64_t(std::bit_cast<std::uint32_t>(ray[i])) |
                   std::uint64_t(std::bit_cast<std::uint32_t>(ray[i + 1])) << 32));
  h = mix64(h ^ triangle);
  return double(h >> 11) * 0x1p-53;
}

// Filter of intersect and occluded queries: keeps a candidate hit with probability P(x).
void alpha_filter(const RTCFilterFunctionNArguments* args) {
  const auto* part = static_cast<const GeometryPart*>(args->geometryUserPtr);
  const auto* context = reinterpret_cast<const SaltedContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const std::uint32_t t = part->scene_triangle(RTCHitN_primID(args->hit, args->N, i));
    const glm::vec2 bary(RTCHitN_u(args->hit, args->N, i), RTCHitN_v(args->hit, args->N, i));
    const float presence = presence_at(*part->alpha_scene, t, bary);
    if (presence >= 1.0f) continue;
    RTCRayN* r = args->ray;
    const unsigned n = args->N;
    const float ray[6] = {RTCRayN_org_x(r, n, i), RTCRayN_org_y(r, n, i), RTCRayN_org_z(r, n, i),
                          RTCRayN_dir_x(r, n, i), RTCRayN_dir_y(r, n, i), RTCRayN_dir_z(r, n, i)};
    if (presence <= 0.0f || !stops(presence, hit_random(context->salt, ray, t))) args->valid[i] = 0;
  }
}

// Lane i of a packet: the segment origin + t direction, t in (tmin, tmax), every mask bit.
void set_lane(RTCRay8& packet, std::size_t i, const glm::vec3& origin, const glm::vec3& direction,
              float tmin, float tmax) {
  packet.org_x[i] = origin.x;
  packet.org_y[i] = origin.y;
  packet.org_z[i] = origin.z;
  packet.dir_x[i] = direction.x;
  packet.dir_y[i] = direction.y;
  packet.dir_z[i] = direction.z;
  packet.tnear[i] = tmin;
  packet.tfar[i] = tmax;
  packet.mask[i] = 0xffffffffu;
}

// The triangles that move with the scene's animation (a vertex in one of its mesh parts).
std::vector<char> moving_triangles(const Scene& scene) {
  std::vector<char> moving(scene.triangles.size(), 0);
  if (!scene.animation || !scene.animation->moves_geometry()) return moving;
  std::vector<char> moving_vertex(scene.positions.size(), 0);
  for (std::uint32_t v : scene.animation->moving_vertices()) moving_vertex[v] = 1;
  for (std::size_t t = 0; t < scene.triangles.size(); ++t) {
    const glm::uvec3 tri = scene.triangles[t];
    moving[t] = moving_vertex[tri.x] || moving_vertex[tri.y] || moving_vertex[tri.z];
  }
  return moving;
}

} // namespace

struct RayScene::Impl {
  ErrorSink errors;
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  GeometryPart fixed, moving; // moving: empty for a static scene

  void check(const std::string& where) {
    if (!errors.message.empty()) throw Error("", where, errors.message);
  }
  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
  std::uint32_t triangle(unsigned geom, unsigned prim) const {
    return (geom == moving.id ? moving : fixed).scene_triangle(prim);
  }

  // Builds the geometry of the triangles t with select[t] == want (all when select is empty).
  void add_part(const Scene& s, const std::vector<char>& select, char want, RTCBuildQuality quality,
                GeometryPart& part);
  // Sets the part's alpha filters (scenes with Mask or Blend materials), commits and attaches it.
  void attach(const Scene& s, GeometryPart& part);
  void copy_vertices(const Scene& s, GeometryPart& part) const {
    for (std::size_t i = 0; i < part.vertices.size(); ++i)
      for (int c = 0; c < 3; ++c) part.vertex_buffer[3 * i + c] = s.positions[part.vertices[i]][c];
  }
};

void RayScene::Impl::add_part(const Scene& s, const std::vector<char>& select, char want,
                              RTCBuildQuality quality, GeometryPart& part) {
  // Every triangle in one geometry: Embree reads the scene's own arrays (no copy of the vertices
  // and triangles: 180 MB at 10M triangles), where the positions' storage reaches 4 bytes past the
  // last one, which Embree reads with 16-byte loads; else the copies below.
  static_assert(sizeof(glm::vec3) == 3 * sizeof(float) &&
                sizeof(glm::uvec3) == 3 * sizeof(unsigned));
  if (select.empty() && !s.triangles.empty() && s.positions.capacity() > s.positions.size()) {
    part.geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetGeometryBuildQuality(part.geometry, quality);
    rtcSetSharedGeometryBuffer(part.geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                               s.positions.data(), 0, sizeof(glm::vec3), s.positions.size());
    rtcSetSharedGeometryBuffer(part.geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                               s.triangles.data(), 0, sizeof(glm::uvec3), s.triangles.size());
    check("embree.buffers");
    attach(s, part);
    return;
  }
  std::vector<std::uint32_t> remap(s.positions.size(), UINT32_MAX);
  std::vector<glm::uvec3> local;
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    if (!select.empty() && select[t] != want) continue;
    glm::uvec3 tri = s.triangles[t];
    for (int c = 0; c < 3; ++c) {
      std::uint32_t& r = remap[tri[c]];
      if (r == UINT32_MAX) {
        r = std::uint32_t(part.vertices.size());
        part.vertices.push_back(tri[c]);
      }
      tri[c] = r;
    }
    local.push_back(tri);
    if (!select.empty()) part.triangles.push_back(std::uint32_t(t));
  }
  if (local.empty()) return;
  part.geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetGeometryBuildQuality(part.geometry, quality);
  part.vertex_buffer = static_cast<float*>(
      rtcSetNewGeometryBuffer(part.geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                              3 * sizeof(float), part.vertices.size()));
  auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(part.geometry, RTC_BUFFER_TYPE_INDEX,
                                                             0, RTC_FORMAT_UINT3,
                                                             3 * sizeof(unsigned), local.size()));
  check("embree.buffers");
  copy_vertices(s, part);
  for (std::size_t i = 0; i < local.size(); ++i)
    for (int c = 0; c < 3; ++c) idx[3 * i + c] = local[i][c];
  attach(s, part);
}

void RayScene::Impl::attach(const Scene& s, GeometryPart& part) {
  if (irad::has_alpha(s)) {
    part.alpha_scene = &s;
    rtcSetGeometryUserData(part.geometry, &part);
    rtcSetGeometryIntersectFilterFunction(part.geometry, alpha_filter);
    rtcSetGeometryOccludedFilterFunction(part.geometry, alpha_filter);
  }
  rtcCommitGeometry(part.geometry);
  part.id = rtcAttachGeometry(scene, part.geometry);
  rtcReleaseGeometry(part.geometry); // the scene holds it
}

RayScene::RayScene(const Scene& scene, BvhQuality quality) : impl_(std::make_unique<Impl>()) {
  const RTCBuildQuality build =
      quality == BvhQuality::High ? RTC_BUILD_QUALITY_HIGH : RTC_BUILD_QUALITY_LOW;
  impl_->device = rtcNewDevice(nullptr);
  if (!impl_->device) throw Error("", "embree", "cannot create an Embree device");
  rtcSetDeviceErrorFunction(impl_->device, on_embree_error, &impl_->errors);
  impl_->scene = rtcNewScene(impl_->device);
  rtcSetSceneBuildQuality(impl_->scene, build);
  const std::vector<char> moving = moving_triangles(scene);
  const bool animated = std::find(moving.begin(), moving.end(), 1) != moving.end();
  // Robust: watertight along shared edges and at corners; without it rays from inside a closed
  // box escaped through its corners (27 of 4000 in HardCases). Fast also keeps the triangles as
  // indices into the vertices (Embree's compact layout) instead of copies: 630 against 718 MiB
  // peak on the sphere box's warm raster.
  // Context filters: intersect_leaving's (a query without one pays nothing for them).
  int flags = RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION;
  if (animated) flags |= RTC_SCENE_FLAG_DYNAMIC;
  if (quality == BvhQuality::Fast) flags |= RTC_SCENE_FLAG_COMPACT;
  rtcSetSceneFlags(impl_->scene, static_cast<RTCSceneFlags>(flags));
  // A static scene is one geometry; an animated one keeps its still triangles in a BVH of the
  // asked quality and the moving ones in a second geometry that update() refits.
  impl_->add_part(scene, animated ? moving : std::vector<char>{}, 0, build, impl_->fixed);
  if (animated) impl_->add_part(scene, moving, 1, RTC_BUILD_QUALITY_REFIT, impl_->moving);
  rtcCommitScene(impl_->scene);
  impl_->check("embree.commit");

  // 1e-5 of the diagonal, and never below a few float ulps of the largest coordinate.
  const float extent = glm::max(glm::length(scene.bounds.lo), glm::length(scene.bounds.hi));
  epsilon_ = glm::max(1e-5f * scene.bounds.diagonal(),
                      32.0f * std::numeric_limits<float>::epsilon() * extent);
}

void RayScene::update(const Scene& scene) {
  for (GeometryPart* p : {&impl_->fixed, &impl_->moving})
    if (p->alpha_scene != nullptr) p->alpha_scene = &scene;
  GeometryPart& part = impl_->moving;
  if (part.geometry == nullptr) return;
  impl_->copy_vertices(scene, part);
  rtcUpdateGeometryBuffer(part.geometry, RTC_BUFFER_TYPE_VERTEX, 0);
  rtcCommitGeometry(part.geometry);
  rtcCommitScene(impl_->scene);
  impl_->check("embree.refit");
}

RayScene::~RayScene() = default;

bool RayScene::has_alpha() const {
  return impl_->fixed.alpha_scene != nullptr || impl_->moving.alpha_scene != nullptr;
}

std::optional<RayHit> RayScene::intersect(const glm::vec3& origin, const glm::vec3& direction,
                                          float tmin, float tmax, std::uint64_t salt) const {
  SaltedContext context(salt);
  RTCRayHit rh{};
  rh.ray.org_x = origin.x;
  rh.ray.org_y = origin.y;
  rh.ray.org_z = origin.z;
  rh.ray.dir_x = direction.x;
  rh.ray.dir_y = direction.y;
  rh.ray.dir_z = direction.z;
  rh.ray.tnear = tmin;
  rh.ray.tfar = tmax;
  rh.ray.mask = 0xffffffffu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->scene, &context.base, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  return RayHit{rh.ray.tfar, impl_->triangle(rh.hit.geomID, rh.hit.primID),
                glm::vec2(rh.hit.u, rh.hit.v)};
}

void RayScene::intersect(const RaySegment* segments, std::size_t n, std::optional<RayHit>* hits,
                         std::uint64_t salt) const {
  intersect_leaving(segments, nullptr, n, hits, salt);
}

void RayScene::intersect_leaving(const RaySegment* segments, const std::uint32_t* leave,
                                 std::size_t n, std::optional<RayHit>* hits,
                                 std::uint64_t salt) const {
  constexpr std::size_t kLanes = 8;
  LeavingContext leaving(salt);
  leaving.parts[0] = &impl_->fixed;
  if (impl_->moving.geometry != nullptr) leaving.parts[1] = &impl_->moving;
  if (leave != nullptr) leaving.salted.base.filter = leaving_filter;
  RTCIntersectContext& context = leaving.salted.base;
  // Embree's packet traversal for rays that run close and alike (the same hits; at a tie between
  // two triangles, either): the thin-wall scan of the 10M sphere box (walk/walls/thin_walls.h, 2
  // threads) 0.81-0.93 s against 1.78-1.86 s without the hint.
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  for (std::size_t first = 0; first < n; first += kLanes) {
    if (leave != nullptr) leaving.leave = leave + first;
    const std::size_t lanes = std::min(kLanes, n - first);
    RTCRayHit8 packet{};
    alignas(32) int valid[kLanes] = {};
    for (std::size_t i = 0; i < lanes; ++i) {
      const RaySegment& s = segments[first + i];
      set_lane(packet.ray, i, s.origin, s.direction, s.tmin, s.tmax);
      packet.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
      valid[i] = -1;
    }
    rtcIntersect8(valid, impl_->scene, &context, &packet);
    for (std::size_t i = 0; i < lanes; ++i) {
      std::optional<RayHit>& hit = hits[first + i];
      hit.reset();
      if (packet.hit.geomID[i] != RTC_INVALID_GEOMETRY_ID)
        hit =
            RayHit{packet.ray.tfar[i], impl_->triangle(packet.hit.geomID[i], packet.hit.primID[i]),
                   glm::vec2(packet.hit.u[i], packet.hit.v[i])};
    }
  }
}

bool RayScene::occluded(const glm::vec3& origin, const glm::vec3& direction, float tmin, float tmax,
                        std::uint64_t salt) const {
  SaltedContext context(salt);
  RTCRay ray{};
  ray.org_x = origin.x;
  ray.org_y = origin.y;
  ray.org_z = origin.z;
  ray.dir_x = direction.x;
  ray.dir_y = direction.y;
  ray.dir_z = direction.z;
  ray.tnear = tmin;
  ray.tfar = tmax;
  ray.mask = 0xffffffffu;
  rtcOccluded1(impl_->scene, &context.base, &ray);
  return ray.tfar < 0.0f; // Embree sets tfar = -inf on a hit
}

void RayScene::occluded(const glm::vec3& origin, const glm::vec3* directions, const float* tmax,
                        std::size_t n, float tmin, bool* blocked, std::uint64_t salt) const {
  constexpr std::size_t kLanes = 8;
  SaltedContext context(salt);
  for (std::size_t first = 0; first < n; first += kLanes) {
    const std::size_t lanes = std::min(kLanes, n - first);
    RTCRay8 packet{};
    alignas(32) int valid[kLanes] = {};
    for (std::size_t i = 0; i < lanes; ++i) {
      set_lane(packet, i, origin, directions[first + i], tmin, tmax[first + i]);
      valid[i] = -1;
    }
    rtcOccluded8(valid, impl_->scene, &context.base, &packet);
    for (std::size_t i = 0; i < lanes; ++i) blocked[first + i] = packet.tfar[i] < 0.0f;
  }
}

} // namespace irad
