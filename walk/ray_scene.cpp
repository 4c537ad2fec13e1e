#include "walk/ray_scene.h"

#include "core/error.h"

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

} // namespace

struct RayScene::Impl {
  ErrorSink errors;
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;

  void check(const std::string& where) {
    if (!errors.message.empty()) throw Error("", where, errors.message);
  }
  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

RayScene::RayScene(const Scene& scene) : impl_(std::make_unique<Impl>()) {
  impl_->device = rtcNewDevice(nullptr);
  if (!impl_->device) throw Error("", "embree", "cannot create an Embree device");
  rtcSetDeviceErrorFunction(impl_->device, on_embree_error, &impl_->errors);
  impl_->scene = rtcNewScene(impl_->device);
  rtcSetSceneBuildQuality(impl_->scene, RTC_BUILD_QUALITY_HIGH);
  // Watertight along shared edges and at corners: without it rays from inside a closed box
  // escaped through its corners (27 of 4000 in HardCases).
  rtcSetSceneFlags(impl_->scene, RTC_SCENE_FLAG_ROBUST);

  RTCGeometry geom = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0,
                                                        RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                        scene.positions.size()));
  auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0,
                                                             RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
                                                             scene.triangles.size()));
  impl_->check("embree.buffers");
  for (std::size_t i = 0; i < scene.positions.size(); ++i)
    for (int c = 0; c < 3; ++c) v[3 * i + c] = scene.positions[i][c];
  for (std::size_t i = 0; i < scene.triangles.size(); ++i)
    for (int c = 0; c < 3; ++c) idx[3 * i + c] = scene.triangles[i][c];
  rtcCommitGeometry(geom);
  rtcAttachGeometry(impl_->scene, geom);
  rtcReleaseGeometry(geom);
  rtcCommitScene(impl_->scene);
  impl_->check("embree.commit");

  // 1e-5 of the diagonal, and never below a few float ulps of the largest coordinate.
  const float extent = glm::max(glm::length(scene.bounds.lo), glm::length(scene.bounds.hi));
  epsilon_ = glm::max(1e-5f * scene.bounds.diagonal(),
                      32.0f * std::numeric_limits<float>::epsilon() * extent);
}

RayScene::~RayScene() = default;

std::optional<RayHit> RayScene::intersect(const glm::vec3& origin, const glm::vec3& direction,
                                          float tmin, float tmax) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
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
  rtcIntersect1(impl_->scene, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  return RayHit{rh.ray.tfar, rh.hit.primID, glm::vec2(rh.hit.u, rh.hit.v)};
}

bool RayScene::occluded(const glm::vec3& origin, const glm::vec3& direction, float tmin,
                        float tmax) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
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
  rtcOccluded1(impl_->scene, &context, &ray);
  return ray.tfar < 0.0f; // Embree sets tfar = -inf on a hit
}

} // namespace irad
