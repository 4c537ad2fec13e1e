#include "core/lights/clamp_field.h"

#include "core/util/error.h"

#include <algorithm>
#include <array>
#include <nanoflann.hpp>
#include <vector>

namespace irad {

namespace {

// Where a VPL's light comes from: its position, or for a mirrored VPL the position it is the
// image of (reflected back through its mirror plane (n, w)).
glm::vec3 source_position(const Vpl& v) {
  if (v.mirror < 0) return v.position;
  const glm::vec3 n(v.mirror_plane);
  return v.position - 2.0f * (glm::dot(n, v.position) + v.mirror_plane.w) * n;
}

bool in_field(const Vpl& v) {
  return v.clamped() && v.mirror < 0;
}

} // namespace

// nanoflann's dataset adaptor over the field's points.
struct ClampField::Index {
  struct Cloud {
    std::vector<glm::vec3> points;
    std::size_t kdtree_get_point_count() const { return points.size(); }
    float kdtree_get_pt(std::size_t i, std::size_t dim) const { return points[i][int(dim)]; }
    template <class Box>
    bool kdtree_get_bbox(Box&) const {
      return false;
    }
  };
  using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, Cloud>,
                                                   Cloud, 3, std::size_t>;
  Cloud cloud;
  std::unique_ptr<Tree> tree;
};

ClampField::ClampField(const VplSet& set, float diagonal, const ClampFieldOptions& options)
    : index_(std::make_unique<Index>()), k_(options.neighbours), scale_(options.scale),
      cap_(options.cap * diagonal), floor_(options.floor * diagonal) {
  if (k_ < 1 || k_ > 64 || !(scale_ > 0.0f) || !(cap_ >= 0.0f) || !(floor_ >= 0.0f))
    throw Error("", "clamp", "the local clamp needs 1 <= k <= 64 and positive scales");
  for (const Vpl& v : set.vpls)
    if (in_field(v)) index_->cloud.points.push_back(v.position);
  if (!index_->cloud.points.empty())
    index_->tree = std::make_unique<Index::Tree>(3, index_->cloud,
                                                 nanoflann::KDTreeSingleIndexAdaptorParams(16));
}

ClampField::~ClampField() = default;

float ClampField::kth(const glm::vec3& y, int k) const {
  // Fewer than k clamped VPLs: their spacing is unknown, so the cap (the global clamp) holds.
  if (index_->cloud.points.size() < static_cast<std::size_t>(k)) return cap_;
  std::array<std::size_t, 65> ids{};
  std::array<float, 65> dist2{};
  const float q[3] = {y.x, y.y, y.z};
  const auto wanted = static_cast<std::size_t>(k);
  const std::size_t found = index_->tree->knnSearch(q, wanted, ids.data(), dist2.data());
  if (found < wanted) return cap_;
  const float r = std::sqrt(dist2[found - 1]);
  return std::clamp(scale_ * r, floor_, std::max(floor_, cap_));
}

float ClampField::at(const glm::vec3& y) const {
  return kth(y, k_);
}

// Leave-one-out: the VPL is one of the field's points, at distance 0 from itself; its k-th nearest
// other VPL is the (k+1)-th.
float ClampField::at(const Vpl& v) const {
  return in_field(v) || v.mirror >= 0 ? kth(source_position(v), k_ + 1) : at(v.position);
}

void assign_clamp_distances(VplSet& set, const ClampField& field) {
  for (Vpl& v : set.vpls) v.clamp_distance = v.clamped() ? field.at(v) : 0.0f;
}

void apply_local_clamp(VplSet& set, float diagonal, const ClampFieldOptions& options) {
  auto field = std::make_shared<const ClampField>(set, diagonal, options);
  assign_clamp_distances(set, *field);
  set.clamp_field = std::move(field);
}

} // namespace irad
