#pragma once
// The clamp distance as a field over the scene's surfaces, following the local density of the
// VPLs instead of the scene's size. The VPL estimator's geometry term
//   G_c(x, y) = cos_y cos_x / max(|x - y|^2, d(y)^2)
// bounds the spike a single VPL at y leaves on receivers closer than the VPLs' spacing there;
// a clamp larger than that spacing only removes light (bias), a smaller one leaves blotches. With
//   d(y) = min(cap, max(floor, scale * r_k(y))),
// r_k(y) the distance from y to its k-th nearest clamped VPL (a VPL leaves itself out), the clamp
// follows the spacing: it shrinks as 1/sqrt(N) where the light paths are dense, so the estimator
// converges to the unclamped transport as N grows, and it stays small in a small room of a large
// level. cap is the global clamp (a fraction of the bounding diagonal): the field never
// clamps more than it.
//
// d is a deterministic function of the point once the VPL set is fixed, so the clamp's residual
// (walk/compensation/bias_compensation.h) R(x) = rho/pi integral cos_x (1 - |x - y|^2 / d(y)^2)+
// L(y -> x) dw recovers exactly what the clamped VPLs leave out, with d(y) at the gather ray's hit.
#include "core/lights/vpl.h"

#include <glm/glm.hpp>
#include <memory>

namespace irad {

struct ClampFieldOptions {
  int neighbours = 8;  // k
  float scale = 0.5f;  // d = scale * r_k (measured: docs/accuracy.md)
  float cap = 0.05f;   // fraction of the bounding diagonal: the largest d (the global clamp)
  float floor = 1e-4f; // fraction of the bounding diagonal: the smallest d
};

class ClampField {
public:
  // Over the clamped (surface, two-sided), unmirrored VPLs of `set`; diagonal: the scene's.
  ClampField(const VplSet& set, float diagonal, const ClampFieldOptions& options);
  ~ClampField();
  ClampField(const ClampField&) = delete;
  ClampField& operator=(const ClampField&) = delete;

  float at(const glm::vec3& y) const; // d(y), world units
  float cap() const { return cap_; }  // the largest d(y) anywhere

  // The field of a VPL: at its position, leaving the VPL itself out (so that d of a VPL is
  // distributed as d of any point: for a Poisson process of VPLs, Slivnyak's theorem; counting
  // itself, the VPLs' clamps would be smaller than the field the residual integrates, and the
  // compensation would overshoot); a mirrored VPL's at the position it is the image of.
  float at(const Vpl& v) const;

private:
  float kth(const glm::vec3& y, int k) const;

  struct Index;
  std::unique_ptr<Index> index_;
  int k_;
  float scale_, cap_, floor_;
};

// Sets Vpl::clamp_distance = field.at(v) on every clamped VPL of `set` (0 elsewhere).
void assign_clamp_distances(VplSet& set, const ClampField& field);

// The local clamp of a walk's VPLs: builds the field over them, assigns their clamp distances and
// keeps the field in set.clamp_field (for the residual).
void apply_local_clamp(VplSet& set, float diagonal, const ClampFieldOptions& options);

} // namespace irad
