#include "core/mesh/hierarchy/mesh_clusters.h"

#include "core/mesh/hierarchy/cluster_levels.h"
#include "core/mesh/planar/flat_components.h"
#include "core/mesh/planar/planar_reduction.h"
#include "core/mesh/position_weld.h"
#include "core/util/freed_memory.h"
#include "core/util/parallel_rows.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <meshoptimizer.h>
#include <numeric>

namespace irad {

namespace {

// welded[v]: the first vertex of v's class in meshoptimizer's `remap` (`unique` classes; ~0u:
// a vertex of no class, welded to itself).
std::vector<std::uint32_t> first_of_class(const std::vector<unsigned int>& remap,
                                          std::size_t unique) {
  std::vector<std::uint32_t> first(unique, ~0u), welded(remap.size());
  for (std::size_t v = 0; v < remap.size(); ++v) {
    welded[v] = static_cast<std::uint32_t>(v);
    if (remap[v] == ~0u) continue;
    if (first[remap[v]] == ~0u) first[remap[v]] = static_cast<std::uint32_t>(v);
    welded[v] = first[remap[v]];
  }
  return welded;
}

// welded[v]: the first vertex equal to v in every attribute the camera passes read (position,
// normal, the texture coordinates, COLOR_0, TANGENT): drawing it instead of v draws the same.
std::vector<std::uint32_t> weld_vertices(const Scene& scene) {
  const std::size_t n = scene.positions.size();
  std::vector<meshopt_Stream> streams;
  const auto add = [&](const auto& values) {
    using V = typename std::decay_t<decltype(values)>::value_type;
    if (values.size() == n) streams.push_back({values.data(), sizeof(V), sizeof(V)});
  };
  add(scene.positions);
  add(scene.normals);
  add(scene.uvs);
  add(scene.uvs1);
  add(scene.colors);
  add(scene.tangents);
  // (meshoptimizer takes a multiple of 3 vertices; the last one or two, ~0u there, stay alone.)
  const std::size_t whole = n - n % 3;
  std::vector<unsigned int> remap(n, ~0u);
  const std::size_t unique = meshopt_generateVertexRemapMulti(remap.data(), nullptr, whole, whole,
                                                              streams.data(), streams.size());
  return first_of_class(remap, unique);
}

// The group of each triangle: its connected component (through shared welded vertices) where
// that has at least `least` triangles, else kRestGroup (all the small components together).
constexpr std::uint32_t kRestGroup = ~0u;
std::vector<std::uint32_t> component_groups(const std::vector<glm::uvec3>& triangles,
                                            std::size_t vertices, std::uint32_t least) {
  std::vector<std::uint32_t> group = triangle_components(triangles, vertices);
  std::vector<std::uint32_t> size(vertices, 0);
  for (std::uint32_t c : group) ++size[c];
  for (std::uint32_t& g : group) g = size[g] >= least ? g : kRestGroup;
  return group;
}

// The camera's groups: component_groups' split by material (`material[t]`: triangle t's),
// numbered in the order of (material, group), so that a material's trees are neighbours.
void split_by_material(std::vector<std::uint32_t>& group,
                       const std::vector<std::uint32_t>& material) {
  std::vector<std::uint64_t> keys(group.size());
  for (std::size_t t = 0; t < group.size(); ++t)
    keys[t] = (std::uint64_t{material[t]} << 32) | group[t];
  std::vector<std::uint64_t> distinct = keys;
  std::sort(distinct.begin(), distinct.end());
  distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
  for (std::size_t t = 0; t < group.size(); ++t)
    group[t] = static_cast<std::uint32_t>(
        std::lower_bound(distinct.begin(), distinct.end(), keys[t]) - distinct.begin());
}

// The indices of a shadow hierarchy over the original part's: the inner meshes add about 1 (each
// height halves the one below), the levels 0.4-0.5 (2.38 on the 10M terrain, 2.45 on the 10M
// sphere box, 2.46 on the 2.1M one).
constexpr std::size_t kIndexRoom = 3;

// One triangle the tree is built over: its welded vertices and its centroid, side by side so
// that a split streams through its range instead of gathering from scattered triangles.
struct TreeTriangle {
  glm::uvec3 vertices;
  glm::vec3 centroid;
};

// What the tree is built over, shared by the Builders of its subtrees.
struct TreeInput {
  std::vector<TreeTriangle> items; // each Builder permutes its own range of it
  float leaf_error = 0.0f; // of the planar reduction the leaves hold (0: the scene's triangles)
};

struct Builder {
  const Scene& scene;
  const ClusterOptions& options;
  TreeInput& in;
  MeshClusters out; // nodes and indices of its subtrees, numbered from 0

  // Splits in.items[begin, end) in two (returns where the second part starts): the binned
  // surface-area heuristic over the centroids (kBins bins per axis; cost = area(box) x count of
  // each side), so that a few large triangles (a room's walls) get regions of their own and do not
  // stretch the boxes of the small ones, which would keep these at full detail (the distance to
  // a box is what the level of detail reads). The median of the longest axis where the
  // centroids do not spread.
  std::size_t split(std::size_t begin, std::size_t end) {
    Bounds centre; // of the centroids
    for (std::size_t k = begin; k < end; ++k) centre.extend(in.items[k].centroid);
    constexpr int kBins = 16;
    const glm::vec3 extent = centre.hi - centre.lo;
    const auto bin_of = [&](const TreeTriangle& t, int axis) {
      const float u = (t.centroid[axis] - centre.lo[axis]) / extent[axis];
      return std::clamp(static_cast<int>(u * kBins), 0, kBins - 1);
    };
    const auto area = [](const Bounds& b) {
      if (b.empty()) return 0.0;
      const glm::dvec3 e(b.hi - b.lo);
      return 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
    };
    // Every axis's bins in one pass (each triangle's vertices gathered once).
    Bounds bins[3][kBins];
    std::size_t bin_counts[3][kBins] = {};
    for (std::size_t k = begin; k < end; ++k) {
      const TreeTriangle& t = in.items[k];
      const glm::vec3 &p0 = scene.positions[t.vertices[0]], &p1 = scene.positions[t.vertices[1]],
                      &p2 = scene.positions[t.vertices[2]];
      const Bounds box{glm::min(glm::min(p0, p1), p2), glm::max(glm::max(p0, p1), p2)};
      for (int axis = 0; axis < 3; ++axis) {
        if (!(extent[axis] > 0.0f)) continue;
        const int b = bin_of(t, axis);
        ++bin_counts[axis][b];
        bins[axis][b].extend(box);
      }
    }
    double best = std::numeric_limits<double>::infinity();
    int best_axis = -1, best_bin = 0;
    for (int axis = 0; axis < 3; ++axis) {
      if (!(extent[axis] > 0.0f)) continue;
      const Bounds* boxes = bins[axis];
      const std::size_t* counts = bin_counts[axis];
      // right[b]: bins b.. merged.
      Bounds right[kBins + 1];
      std::size_t right_count[kBins + 1] = {};
      for (int b = kBins - 1; b >= 0; --b) {
        right[b] = right[b + 1];
        right[b].extend(boxes[b]);
        right_count[b] = right_count[b + 1] + counts[b];
      }
      Bounds left;
      std::size_t left_count = 0;
      for (int b = 0; b + 1 < kBins; ++b) {
        left.extend(boxes[b]);
        left_count += counts[b];
        if (left_count == 0 || right_count[b + 1] == 0) continue;
        const double cost = area(left) * static_cast<double>(left_count) +
                            area(right[b + 1]) * static_cast<double>(right_count[b + 1]);
        if (cost < best) {
          best = cost;
          best_axis = axis;
          best_bin = b;
        }
      }
    }
    const auto first = in.items.begin() + static_cast<std::ptrdiff_t>(begin);
    const auto last = in.items.begin() + static_cast<std::ptrdiff_t>(end);
    if (best_axis >= 0)
      return static_cast<std::size_t>(
          std::partition(first, last,
                         [&](const TreeTriangle& t) { return bin_of(t, best_axis) <= best_bin; }) -
          in.items.begin());
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0
                     : extent.y >= extent.z                       ? 1
                                                                  : 2;
    const std::size_t mid = begin + (end - begin) / 2;
    std::nth_element(first, in.items.begin() + static_cast<std::ptrdiff_t>(mid), last,
                     [&](const TreeTriangle& a, const TreeTriangle& b) {
                       return a.centroid[axis] < b.centroid[axis];
                     });
    return mid;
  }

  // Node over in.items[begin, end): a leaf writes its triangles to the original part, in
  // depth-first order, so every subtree's leaves are contiguous there.
  std::int32_t build(std::size_t begin, std::size_t end) {
    const auto id = static_cast<std::int32_t>(out.nodes.size());
    out.nodes.emplace_back();
    if (end - begin <= options.leaf_triangles) {
      ClusterNode& node = out.nodes.back();
      node.error = in.leaf_error;
      node.leaf_first = node.mesh_first = static_cast<std::uint32_t>(out.indices.size());
      for (std::size_t k = begin; k < end; ++k) {
        const glm::uvec3& t = in.items[k].vertices;
        for (int c = 0; c < 3; ++c) {
          out.indices.push_back(t[c]);
          node.bounds.extend(scene.positions[t[c]]);
        }
      }
      node.leaf_count = node.mesh_count = static_cast<std::uint32_t>(3 * (end - begin));
      return id;
    }
    const std::size_t mid = split(begin, end);
    const std::int32_t c0 = build(begin, mid);
    const std::int32_t c1 = build(mid, end);
    join(id, c0, c1);
    return id;
  }

  // Node id as the parent of c0 and c1.
  void join(std::int32_t id, std::int32_t c0, std::int32_t c1) {
    ClusterNode& node = out.nodes[static_cast<std::size_t>(id)];
    const ClusterNode &a = out.nodes[static_cast<std::size_t>(c0)],
                      &b = out.nodes[static_cast<std::size_t>(c1)];
    node.children[0] = c0;
    node.children[1] = c1;
    node.bounds = a.bounds;
    node.bounds.extend(b.bounds);
    node.leaf_first = a.leaf_first;
    node.leaf_count = a.leaf_count + b.leaf_count;
  }

  // build(begin, end), the two subtrees below each node of the top `depth` levels built on two
  // threads, each by its own Builder, then appended in depth-first order: the same nodes and
  // indices as build's.
  std::int32_t build_parallel(std::size_t begin, std::size_t end, int depth) {
    if (depth <= 0 || end - begin <= options.leaf_triangles) return build(begin, end);
    const auto id = static_cast<std::int32_t>(out.nodes.size());
    out.nodes.emplace_back();
    const std::size_t mid = split(begin, end);
    Builder halves[2] = {{scene, options, in, {}}, {scene, options, in, {}}};
    const std::size_t ranges[3] = {begin, mid, end};
    parallel_tasks(2, 2, [&](int h, unsigned) {
      const auto k = static_cast<std::size_t>(h);
      halves[k].out.indices.reserve(3 * (ranges[k + 1] - ranges[k])); // its leaves' indices
      halves[k].build_parallel(ranges[k], ranges[k + 1], depth - 1);
    });
    const std::int32_t c0 = append(halves[0].out);
    join(id, c0, append(halves[1].out));
    return id;
  }

  // Appends a subtree another Builder built (its nodes and indices numbered from 0); returns its
  // root's id here.
  std::int32_t append(const MeshClusters& sub) {
    const auto node_offset = static_cast<std::int32_t>(out.nodes.size());
    const auto index_offset = static_cast<std::uint32_t>(out.indices.size());
    for (ClusterNode n : sub.nodes) {
      for (std::int32_t& c : n.children)
        if (c >= 0) c += node_offset;
      n.leaf_first += index_offset;
      if (n.leaf()) n.mesh_first += index_offset; // an inner node's mesh comes later
      out.nodes.push_back(n);
    }
    out.indices.insert(out.indices.end(), sub.indices.begin(), sub.indices.end());
    return node_offset;
  }
};

// The tree's triangles in `order`, each with its centroid, on all cores.
std::vector<TreeTriangle> tree_items(const Scene& scene, const std::vector<glm::uvec3>& triangles,
                                     const std::vector<std::uint32_t>& order) {
  std::vector<TreeTriangle> items(order.size());
  parallel_chunks(order.size(), [&](std::size_t first, std::size_t end) {
    for (std::size_t k = first; k < end; ++k) {
      const glm::uvec3& v = triangles[order[k]];
      items[k] = {v, (scene.positions[v.x] + scene.positions[v.y] + scene.positions[v.z]) / 3.0f};
    }
  });
  return items;
}

// The camera's bound on what a node's mesh changes: the larger of its distance from the surface
// and its longest edge, across which it interpolates the vertices' normals and texture
// coordinates (a mesh whose edges stay below a pixel shades within the pixel it covers).
// Node by node on all cores.
void bound_by_edges(const Scene& scene, MeshClusters& out, unsigned threads) {
  parallel_rows(static_cast<int>(out.nodes.size()), threads, [&](int n) {
    ClusterNode& node = out.nodes[static_cast<std::size_t>(n)];
    if (node.leaf()) return;
    float longest = 0.0f;
    for (std::uint32_t k = node.mesh_first; k < node.mesh_first + node.mesh_count; k += 3)
      for (int e = 0; e < 3; ++e) {
        const glm::vec3 d =
            scene.positions[out.indices[k + e]] - scene.positions[out.indices[k + (e + 1) % 3]];
        longest = std::max(longest, glm::dot(d, d));
      }
    node.error = std::max(node.error, std::sqrt(longest));
  });
}

// The opaque triangles, their vertices welded (weld_vertices for the camera's hierarchy, else
// weld_positions); their scene triangle ids ascending into out.triangles where some triangle is
// left out.
std::vector<glm::uvec3> welded_triangles(const Scene& scene, const ClusterOptions& options,
                                         MeshClusters& out) {
  const std::vector<std::uint32_t> welded =
      options.camera ? weld_vertices(scene) : weld_positions(scene.positions, options.threads);
  const auto opaque = [&](std::size_t t) {
    return scene.material_of(t).alpha_mode == AlphaMode::Opaque;
  };
  bool every = true;
  for (std::size_t t = 0; t < scene.triangle_count() && every; ++t) every = opaque(t);
  std::vector<glm::uvec3> triangles;
  triangles.reserve(scene.triangle_count());
  for (std::size_t t = 0; t < scene.triangle_count(); ++t) {
    if (!every && !opaque(t)) continue;
    const glm::uvec3 v = scene.triangles[t];
    if (!every) out.triangles.push_back(static_cast<std::uint32_t>(t));
    triangles.emplace_back(welded[v.x], welded[v.y], welded[v.z]);
  }
  return triangles;
}

// The trees over `triangles` (welded; leaves' error leaf_error) into out: one per connected
// component of at least a leaf's triangles, one for all the others (the camera's split by
// material too); out.roots, the nodes, the original part of out.indices. Returns which nodes
// are roots of one connected component. What the build sorts and splits with (the triangles with
// their centroids, 24 bytes each, and their groups) is freed on return, before the
// simplifications.
std::vector<bool> build_trees(const Scene& scene, const ClusterOptions& options,
                              std::vector<glm::uvec3> triangles, float leaf_error,
                              MeshClusters& out) {
  std::vector<std::uint32_t> group =
      component_groups(triangles, scene.positions.size(), options.leaf_triangles);
  std::vector<std::uint32_t> material; // the camera's: of each triangle of the tree
  if (options.camera) {
    material.resize(triangles.size());
    for (std::size_t t = 0; t < material.size(); ++t)
      material[t] = scene.triangle_material[out.triangles.empty() ? t : out.triangles[t]];
    split_by_material(group, material);
  }
  std::vector<std::uint32_t> order(triangles.size());
  std::iota(order.begin(), order.end(), 0u);
  const auto by_group = [&](std::uint32_t x, std::uint32_t y) { return group[x] < group[y]; };
  if (!std::is_sorted(order.begin(), order.end(), by_group)) // (one component: it is)
    std::stable_sort(order.begin(), order.end(), by_group);
  TreeInput in{tree_items(scene, triangles, order), leaf_error};
  triangles = {};
  Builder b{scene, options, in, std::move(out)};
  // Room for the inner nodes' meshes and the levels after the original part, reserved now, so
  // that appending them moves nothing: a moved array would hold its old and new copies at once
  // (the original part and the meshes again: 240 MiB on the 10M terrain). Pages no index is
  // written to are never given to the process.
  b.out.indices.reserve(3 * in.items.size() * kIndexRoom);
  std::vector<bool> whole;
  // The top levels split on one thread, the subtrees below them on as many as the build has.
  int depth = 0;
  while ((1u << depth) < worker_count(options.threads, 1 << 30)) ++depth;
  for (std::size_t begin = 0; begin < order.size();) {
    std::size_t end = begin + 1;
    while (end < order.size() && group[order[end]] == group[order[begin]]) ++end;
    const std::int32_t root = b.build_parallel(begin, end, depth);
    b.out.roots.push_back(root);
    if (options.camera) b.out.root_materials.push_back(material[order[begin]]);
    whole.resize(b.out.nodes.size(), false);
    whole[static_cast<std::size_t>(root)] = group[order[begin]] != kRestGroup;
    begin = end;
  }
  b.out.original_indices = b.out.indices.size();
  out = std::move(b.out);
  return whole;
}

// The planar reduction's plane thickness, relative to the scene's diagonal (the shadow passes'
// error floor is 1e-5 of it, raster/shadow/shadow_atlas.cpp).
constexpr float kPlanar = 1e-6f;

} // namespace

float distance_to(const Bounds& b, const glm::vec3& p) {
  return glm::length(glm::max(glm::max(b.lo - p, p - b.hi), glm::vec3(0.0f)));
}

ClusterOptions shadow_cluster_options(const ShadowLodOptions& lod) {
  ClusterOptions o;
  o.simplify = lod.mode == ShadowLodMode::On;
  o.defer_levels = o.simplify && lod.levels_on_demand;
  return o;
}

int level_step(std::uint32_t leaf_triangles) {
  return leaf_triangles >= kQuarteringLeaf ? 4 : 2;
}

bool leaf_levels(std::uint32_t leaf_triangles) {
  return leaf_triangles < kQuarteringLeaf;
}

std::uint32_t automatic_leaf_triangles(std::size_t triangles) {
  std::uint32_t leaf = 128;
  while (leaf < 1024 && static_cast<std::size_t>(leaf) * 512 < triangles) leaf *= 2;
  return leaf;
}

MeshClusters build_mesh_clusters(const Scene& scene, const ClusterOptions& requested,
                                 StageTimes* times) {
  StageTimes own;
  StageTimes& stages = times ? *times : own;
  auto start = StageTimes::Clock::now();
  ClusterOptions options = requested;
  if (options.leaf_triangles == 0)
    options.leaf_triangles = automatic_leaf_triangles(scene.triangle_count());
  MeshClusters out;
  std::vector<glm::uvec3> triangles = welded_triangles(scene, options, out);
  start = stages.lap("weld", start);
  float leaf_error = 0.0f;
  if (options.simplify && !options.camera) {
    // Flat parts first reduced exactly (to 2 kPlanar of the surface): the regions' locked
    // borders then cost what their outlines need, not the tessellation's resolution.
    const float epsilon = kPlanar * scene.bounds.diagonal();
    const std::size_t before = triangles.size();
    PlanarReduction reduced =
        reduce_flat_components(scene.positions, std::move(triangles), epsilon);
    triangles = std::move(reduced.triangles);
    if (reduced.collapses > 0 || triangles.size() < before) leaf_error = 2.0f * epsilon;
  }
  start = stages.lap("planar", start);
  if (triangles.empty()) return out;
  const std::vector<bool> whole =
      build_trees(scene, options, std::move(triangles), leaf_error, out);
  // The weld's, the planar reduction's and the tree's transients, freed by now, go back: the
  // meshes and levels that follow are smaller, and the process's peak would keep them.
  release_freed_memory();
  start = stages.lap("tree", start);
  simplify_inner_nodes(scene, out, options.simplify || options.camera, options.threads);
  if (options.camera) bound_by_edges(scene, out, options.threads);
  start = stages.lap("inner", start);
  if (options.simplify && !options.camera)
    add_coarser_levels(scene, out, options.max_levels, level_step(options.leaf_triangles), whole,
                       leaf_levels(options.leaf_triangles), options.defer_levels, options.threads);
  stages.lap("levels", start);
  return out;
}

} // namespace irad
