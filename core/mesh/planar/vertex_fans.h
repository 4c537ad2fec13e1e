#pragma once
// The triangles around each vertex, in one array (no allocation per vertex): the fan of v is
// list[first[v], first[v + 1]), its triangles in ascending order. Shared by the flat-component
// sampling (core/mesh/planar/flat_components.h) and the planar reduction
// (core/mesh/planar/planar_reduction.h).
#include <cstdint>
#include <glm/vec3.hpp>
#include <numeric>
#include <vector>

namespace irad {

struct VertexFans {
  std::vector<std::uint32_t> first, list;

  // Every triangle t with keep(t) in the fans of those of its vertices v with want(v) (the
  // others' fans stay empty).
  template <class Keep, class Want>
  VertexFans(const std::vector<glm::uvec3>& triangles, std::size_t vertices, Keep keep, Want want)
      : first(vertices + 1, 0) {
    for (std::uint32_t t = 0; t < triangles.size(); ++t)
      if (keep(t))
        for (int c = 0; c < 3; ++c)
          if (want(triangles[t][c])) ++first[triangles[t][c] + 1];
    std::partial_sum(first.begin(), first.end(), first.begin());
    list.resize(first.back());
    std::vector<std::uint32_t> next(first.begin(), first.end() - 1);
    for (std::uint32_t t = 0; t < triangles.size(); ++t)
      if (keep(t))
        for (int c = 0; c < 3; ++c)
          if (want(triangles[t][c])) list[next[triangles[t][c]]++] = t;
  }
};

} // namespace irad
