#include "core/mesh/mesh_clusters.h"

#include "core/mesh/flat_components.h"
#include "core/mesh/planar_reduction.h"
#include "core/util/parallel_rows.h"

#include <algorithm>
#include <limits>
#include <meshoptimizer.h>
#include <numeric>

namespace irad {

namespace {

// welded[v]: the first vertex at v's position (bitwise equal floats).
std::vector<std::uint32_t> weld_positions(const Scene& scene) {
  const std::size_t n = scene.positions.size();
  std::vector<unsigned int> remap(n);
  const std::size_t unique = meshopt_generateVertexRemap(
      remap.data(), nullptr, n, scene.positions.data(), n, sizeof(glm::vec3));
  std::vector<std::uint32_t> first(unique, ~0u), welded(n);
  for (std::size_t v = 0; v < n; ++v) {
    if (first[remap[v]] == ~0u) first[remap[v]] = static_cast<std::uint32_t>(v);
    welded[v] = first[remap[v]];
  }
  return welded;
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

// What the tree is built over, shared by the Builders of its subtrees.
struct TreeInput {
  std::vector<glm::uvec3> triangles; // welded, in the order `order` permutes
  std::vector<glm::vec3> centroids;
  std::vector<std::uint32_t> order; // each Builder permutes its own range of it
  float leaf_error = 0.0f; // of the planar reduction the leaves hold (0: the scene's triangles)
};

struct Builder {
  const Scene& scene;
  const ClusterOptions& options;
  TreeInput& in;
  MeshClusters out; // nodes and indices of its subtrees, numbered from 0

  // Splits in.order[begin, end) in two (returns where the second part starts): the binned
  // surface-area heuristic over the centroids (kBins bins per axis; cost = area(box) x count of
  // each side), so that a few large triangles (a room's walls) get regions of their own and do not
  // stretch the boxes of the small ones, which would keep these at full detail (the distance to
  // a box is what the level of detail reads). The median of the longest axis where the
  // centroids do not spread.
  std::size_t split(std::size_t begin, std::size_t end, const Bounds& centre) {
    constexpr int kBins = 16;
    const glm::vec3 extent = centre.hi - centre.lo;
    const auto bin_of = [&](std::uint32_t t, int axis) {
      const float u = (in.centroids[t][axis] - centre.lo[axis]) / extent[axis];
      return std::clamp(static_cast<int>(u * kBins), 0, kBins - 1);
    };
    const auto area = [](const Bounds& b) {
      if (b.empty()) return 0.0;
      const glm::dvec3 e(b.hi - b.lo);
      return 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
    };
    double best = std::numeric_limits<double>::infinity();
    int best_axis = -1, best_bin = 0;
    for (int axis = 0; axis < 3; ++axis) {
      if (!(extent[axis] > 0.0f)) continue;
      Bounds boxes[kBins];
      std::size_t counts[kBins] = {};
      for (std::size_t k = begin; k < end; ++k) {
        const std::uint32_t t = in.order[k];
        const int b = bin_of(t, axis);
        ++counts[b];
        for (int c = 0; c < 3; ++c) boxes[b].extend(scene.positions[in.triangles[t][c]]);
      }
      // right[b]: bins b.. merged.
      Bounds right[kBins + 1];
      std::size_t right_count[kBins + 1] = {};
      for (int b = kBins - 1; b >= 0; --b) {
        right[b] = right[b + 1];
        right[b].extend(boxes[b].lo);
        right[b].extend(boxes[b].hi);
        if (boxes[b].empty()) right[b] = right[b + 1];
        right_count[b] = right_count[b + 1] + counts[b];
      }
      Bounds left;
      std::size_t left_count = 0;
      for (int b = 0; b + 1 < kBins; ++b) {
        if (!boxes[b].empty()) {
          left.extend(boxes[b].lo);
          left.extend(boxes[b].hi);
        }
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
    const auto first = in.order.begin() + static_cast<std::ptrdiff_t>(begin);
    const auto last = in.order.begin() + static_cast<std::ptrdiff_t>(end);
    if (best_axis >= 0)
      return static_cast<std::size_t>(
          std::partition(first, last,
                         [&](std::uint32_t t) { return bin_of(t, best_axis) <= best_bin; }) -
          in.order.begin());
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0
                     : extent.y >= extent.z                       ? 1
                                                                  : 2;
    const std::size_t mid = begin + (end - begin) / 2;
    std::nth_element(first, in.order.begin() + static_cast<std::ptrdiff_t>(mid), last,
                     [&](std::uint32_t a, std::uint32_t b) {
                       return in.centroids[a][axis] < in.centroids[b][axis];
                     });
    return mid;
  }

  // Node over in.order[begin, end): a leaf writes its triangles to the original part, in
  // depth-first order, so every subtree's leaves are contiguous there.
  std::int32_t build(std::size_t begin, std::size_t end) {
    const auto id = static_cast<std::int32_t>(out.nodes.size());
    out.nodes.emplace_back();
    Bounds centre;
    for (std::size_t k = begin; k < end; ++k) centre.extend(in.centroids[in.order[k]]);
    if (end - begin <= options.leaf_triangles) {
      ClusterNode& node = out.nodes.back();
      node.error = in.leaf_error;
      node.leaf_first = node.mesh_first = static_cast<std::uint32_t>(out.indices.size());
      for (std::size_t k = begin; k < end; ++k) {
        const glm::uvec3& t = in.triangles[in.order[k]];
        for (int c = 0; c < 3; ++c) {
          out.indices.push_back(t[c]);
          node.bounds.extend(scene.positions[t[c]]);
        }
      }
      node.leaf_count = node.mesh_count = static_cast<std::uint32_t>(3 * (end - begin));
      return id;
    }
    const std::size_t mid = split(begin, end, centre);
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
    node.bounds.extend(b.bounds.lo);
    node.bounds.extend(b.bounds.hi);
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
    Bounds centre;
    for (std::size_t k = begin; k < end; ++k) centre.extend(in.centroids[in.order[k]]);
    const std::size_t mid = split(begin, end, centre);
    Builder halves[2] = {{scene, options, in, {}}, {scene, options, in, {}}};
    const std::size_t ranges[3] = {begin, mid, end};
    parallel_tasks(2, 2, [&](int h, unsigned) {
      const auto k = static_cast<std::size_t>(h);
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

// The planar reduction's plane thickness, relative to the scene's diagonal (the shadow passes'
// error floor is 1e-5 of it, raster/shadow/shadow_atlas.cpp).
constexpr float kPlanar = 1e-6f;

// Relative error (of the mesh's extent) below which meshoptimizer's collapses count as exact.
constexpr float kExact = 1e-6f;

// `input` simplified to 1/divisor of its triangles (divisor 0: as far as target_error, relative
// to the extent, allows), its open edges (the region's border) locked;
// error: this step's (world units).
struct Simplified {
  std::vector<std::uint32_t> indices;
  float error = 0.0f;
};
Simplified simplify_union(const Scene& scene, const std::vector<std::uint32_t>& input,
                          std::vector<std::uint32_t>& local_of, std::size_t divisor = 2,
                          float target_error = 1.0f) {
  // A compact vertex array of the vertices used (meshoptimizer scales by all it is given).
  std::vector<std::uint32_t> global, local(input.size());
  std::vector<glm::vec3> positions;
  for (std::size_t k = 0; k < input.size(); ++k) {
    std::uint32_t& l = local_of[input[k]];
    if (l == ~0u) {
      l = static_cast<std::uint32_t>(global.size());
      global.push_back(input[k]);
      positions.push_back(scene.positions[input[k]]);
    }
    local[k] = l;
  }
  for (std::uint32_t g : global) local_of[g] = ~0u;
  Simplified s;
  std::vector<std::uint32_t> dest(input.size());
  const std::size_t target = divisor == 0 ? 0 : input.size() / (3 * divisor) * 3;
  float relative = 0.0f;
  const std::size_t count = meshopt_simplify(
      dest.data(), local.data(), local.size(), &positions[0].x, positions.size(), sizeof(glm::vec3),
      target, target_error, meshopt_SimplifyLockBorder, &relative);
  s.error = relative * meshopt_simplifyScale(&positions[0].x, positions.size(), sizeof(glm::vec3));
  s.indices.resize(count);
  for (std::size_t k = 0; k < count; ++k) s.indices[k] = global[dest[k]];
  return s;
}

// Per worker of parallel_tasks, simplify_union's map from scene vertex to compact index (all
// ~0u between calls), made on the worker's first task.
class LocalMaps {
public:
  LocalMaps(std::size_t vertices, unsigned workers) : vertices_(vertices), maps_(workers) {}
  std::vector<std::uint32_t>& of(unsigned worker) {
    std::vector<std::uint32_t>& m = maps_[worker];
    if (m.empty()) m.assign(vertices_, ~0u);
    return m;
  }

private:
  std::size_t vertices_;
  std::vector<std::vector<std::uint32_t>> maps_;
};

// Each node's height: leaves 0, a parent one above its higher child.
std::vector<int> node_heights(const MeshClusters& out) {
  std::vector<int> height(out.nodes.size(), 0);
  for (std::size_t n = out.nodes.size(); n-- > 0;) { // children after their parents
    const ClusterNode& node = out.nodes[n];
    if (!node.leaf())
      height[n] = 1 + std::max(height[static_cast<std::size_t>(node.children[0])],
                               height[static_cast<std::size_t>(node.children[1])]);
  }
  return height;
}

// The nodes by height, lowest first: a node's children all lie in the groups before its own.
std::vector<std::vector<std::int32_t>> nodes_by_height(const MeshClusters& out) {
  const std::vector<int> height = node_heights(out);
  std::vector<std::vector<std::int32_t>> groups(1);
  for (std::size_t n = out.nodes.size(); n-- > 0;) {
    const auto h = static_cast<std::size_t>(height[n]);
    if (h >= groups.size()) groups.resize(h + 1);
    groups[h].push_back(static_cast<std::int32_t>(n));
  }
  return groups;
}

// The inner nodes' meshes, height by height (each height's nodes in parallel: a node reads only
// its children's meshes), then appended in node order: the same result on any number of threads.
void simplify_inner_nodes(const Scene& scene, MeshClusters& out, bool simplify, unsigned threads) {
  std::vector<std::vector<std::uint32_t>> meshes(out.nodes.size());
  LocalMaps local(scene.positions.size(),
                  worker_count(threads, static_cast<int>(out.nodes.size())));
  const auto mesh_of = [&](std::int32_t n) {
    const ClusterNode& c = out.nodes[static_cast<std::size_t>(n)];
    const std::vector<std::uint32_t>& m = meshes[static_cast<std::size_t>(n)];
    return c.leaf() ? std::vector<std::uint32_t>(out.indices.begin() + c.mesh_first,
                                                 out.indices.begin() + c.mesh_first + c.mesh_count)
                    : m;
  };
  const auto simplify_node = [&](std::size_t n, unsigned worker) {
    ClusterNode& node = out.nodes[n];
    std::vector<std::uint32_t> input = mesh_of(node.children[0]);
    const std::vector<std::uint32_t> second = mesh_of(node.children[1]);
    input.insert(input.end(), second.begin(), second.end());
    const float below = std::max(out.nodes[static_cast<std::size_t>(node.children[0])].error,
                                 out.nodes[static_cast<std::size_t>(node.children[1])].error);
    node.error = below;
    if (simplify && !input.empty()) {
      Simplified s = simplify_union(scene, input, local.of(worker));
      if (s.indices.size() < input.size()) {
        input = std::move(s.indices);
        node.error = below + s.error;
      }
    }
    meshes[n] = std::move(input);
  };
  const std::vector<std::vector<std::int32_t>> groups = nodes_by_height(out);
  for (std::size_t h = 1; h < groups.size(); ++h) {
    const std::vector<std::int32_t>& group = groups[h];
    parallel_tasks(static_cast<int>(group.size()), threads, [&](int k, unsigned worker) {
      simplify_node(static_cast<std::size_t>(group[static_cast<std::size_t>(k)]), worker);
    });
  }
  for (std::size_t n = 0; n < out.nodes.size(); ++n) {
    ClusterNode& node = out.nodes[n];
    if (node.leaf()) continue;
    node.mesh_first = static_cast<std::uint32_t>(out.indices.size());
    node.mesh_count = static_cast<std::uint32_t>(meshes[n].size());
    out.indices.insert(out.indices.end(), meshes[n].begin(), meshes[n].end());
  }
}

// One node's coarser levels (add_coarser_levels), meshes one after another in `indices`.
struct NodeLevels {
  std::vector<ClusterLevel> levels; // first: offsets into `indices`
  std::vector<std::uint32_t> indices;
};

// A component root's levels start from the cut of its tree through the nodes of at most this
// height: their meshes, each about 2^-height of its region's triangles, are the whole
// component's at a quarter of the cost of simplifying the original triangles that far.
constexpr int kWholeCutHeight = 2;

// The meshes of the cut below `root` through the nodes of height at most kWholeCutHeight, joined:
// one seamless mesh of the component (neighbouring regions share their locked borders);
// `error`: the largest of theirs.
std::vector<std::uint32_t> shallow_cut(const MeshClusters& out, std::size_t root,
                                       const std::vector<int>& height, float& error) {
  std::vector<std::uint32_t> mesh;
  error = 0.0f;
  std::vector<std::size_t> stack{root};
  while (!stack.empty()) {
    const std::size_t n = stack.back();
    stack.pop_back();
    const ClusterNode& node = out.nodes[n];
    if (height[n] > kWholeCutHeight) {
      stack.push_back(static_cast<std::size_t>(node.children[1]));
      stack.push_back(static_cast<std::size_t>(node.children[0]));
      continue;
    }
    mesh.insert(mesh.end(), out.indices.begin() + node.mesh_first,
                out.indices.begin() + node.mesh_first + node.mesh_count);
    error = std::max(error, node.error);
  }
  return mesh;
}

// Its mesh halved again and again (the border still locked) while that removes at least a tenth
// of the triangles. A root of one connected component (`whole`) starts from the shallow cut of
// its tree instead and quarters it: no region border inside it is locked, so a closed surface
// simplifies as far as its error allows.
NodeLevels coarser_levels(const Scene& scene, const MeshClusters& out, std::size_t n, bool whole,
                          int max_levels, const std::vector<int>& height,
                          std::vector<std::uint32_t>& local_of) {
  const ClusterNode& node = out.nodes[n];
  float error = node.error;
  std::vector<std::uint32_t> mesh =
      whole ? shallow_cut(out, n, height, error)
            : std::vector<std::uint32_t>(out.indices.begin() + node.mesh_first,
                                         out.indices.begin() + node.mesh_first + node.mesh_count);
  NodeLevels result;
  const auto keep = [&] {
    result.levels.push_back({error, static_cast<std::uint32_t>(result.indices.size()),
                             static_cast<std::uint32_t>(mesh.size())});
    result.indices.insert(result.indices.end(), mesh.begin(), mesh.end());
  };
  // First what simplifies without error (coplanar triangles: flat walls to their borders),
  // then quarters or halves, whatever that costs.
  if (!mesh.empty()) {
    Simplified s = simplify_union(scene, mesh, local_of, 0, kExact);
    if (10 * s.indices.size() <= 9 * mesh.size()) {
      error += s.error;
      mesh = std::move(s.indices);
      keep();
    }
  }
  for (int l = 0; l < max_levels && !mesh.empty(); ++l) {
    Simplified s = simplify_union(scene, mesh, local_of, whole ? 4 : 2);
    if (10 * s.indices.size() > 9 * mesh.size()) break;
    error += s.error;
    mesh = std::move(s.indices);
    keep();
  }
  return result;
}

// Every node's coarser levels, in parallel (the component roots first: the longest tasks), then
// appended in node order: the same result on any number of threads.
void add_coarser_levels(const Scene& scene, MeshClusters& out, int max_levels,
                        const std::vector<bool>& whole, unsigned threads) {
  std::vector<std::size_t> order(out.nodes.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_partition(order.begin(), order.end(), [&](std::size_t n) { return whole[n]; });
  std::vector<NodeLevels> levels(out.nodes.size());
  const std::vector<int> height = node_heights(out);
  LocalMaps local(scene.positions.size(), worker_count(threads, static_cast<int>(order.size())));
  parallel_tasks(static_cast<int>(order.size()), threads, [&](int k, unsigned worker) {
    const std::size_t n = order[static_cast<std::size_t>(k)];
    levels[n] = coarser_levels(scene, out, n, whole[n], max_levels, height, local.of(worker));
  });
  for (std::size_t n = 0; n < out.nodes.size(); ++n) {
    ClusterNode& node = out.nodes[n];
    node.levels_first = static_cast<std::uint32_t>(out.levels.size());
    const auto base = static_cast<std::uint32_t>(out.indices.size());
    for (ClusterLevel level : levels[n].levels) {
      level.first += base;
      out.levels.push_back(level);
    }
    out.indices.insert(out.indices.end(), levels[n].indices.begin(), levels[n].indices.end());
    node.levels_count = static_cast<std::uint32_t>(levels[n].levels.size());
    levels[n] = {};
  }
}

} // namespace

float distance_to(const Bounds& b, const glm::vec3& p) {
  return glm::length(glm::max(glm::max(b.lo - p, p - b.hi), glm::vec3(0.0f)));
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
  TreeInput in;
  Builder b{scene, options, in, {}};
  const std::vector<std::uint32_t> welded = weld_positions(scene);
  for (std::size_t t = 0; t < scene.triangle_count(); ++t) {
    if (scene.material_of(t).alpha_mode != AlphaMode::Opaque) continue;
    const glm::uvec3 v = scene.triangles[t];
    b.out.triangles.push_back(static_cast<std::uint32_t>(t));
    in.triangles.emplace_back(welded[v.x], welded[v.y], welded[v.z]);
  }
  start = stages.lap("weld", start);
  if (options.simplify) {
    // Flat parts first reduced exactly (to 2 kPlanar of the surface): the regions' locked
    // borders then cost what their outlines need, not the tessellation's resolution.
    const float epsilon = kPlanar * scene.bounds.diagonal();
    PlanarReduction reduced = reduce_flat_components(scene.positions, in.triangles, epsilon);
    if (reduced.collapses > 0 || reduced.triangles.size() < in.triangles.size()) {
      in.triangles = std::move(reduced.triangles);
      in.leaf_error = 2.0f * epsilon;
    }
  }
  start = stages.lap("planar", start);
  for (const glm::uvec3& v : in.triangles)
    in.centroids.push_back((scene.positions[v.x] + scene.positions[v.y] + scene.positions[v.z]) /
                           3.0f);
  if (in.triangles.empty()) return std::move(b.out);
  // One tree per connected component of at least a leaf's triangles, one for all the others.
  const std::vector<std::uint32_t> group =
      component_groups(in.triangles, scene.positions.size(), options.leaf_triangles);
  in.order.resize(in.triangles.size());
  std::iota(in.order.begin(), in.order.end(), 0u);
  std::stable_sort(in.order.begin(), in.order.end(),
                   [&](std::uint32_t x, std::uint32_t y) { return group[x] < group[y]; });
  b.out.indices.reserve(3 * in.triangles.size());
  std::vector<bool> whole;
  // The top levels split on one thread, the subtrees below them on as many as the build has.
  int depth = 0;
  while ((1u << depth) < worker_count(options.threads, 1 << 30)) ++depth;
  for (std::size_t begin = 0; begin < in.order.size();) {
    std::size_t end = begin + 1;
    while (end < in.order.size() && group[in.order[end]] == group[in.order[begin]]) ++end;
    const std::int32_t root = b.build_parallel(begin, end, depth);
    b.out.roots.push_back(root);
    whole.resize(b.out.nodes.size(), false);
    whole[static_cast<std::size_t>(root)] = group[in.order[begin]] != kRestGroup;
    begin = end;
  }
  b.out.original_indices = b.out.indices.size();
  start = stages.lap("tree", start);
  simplify_inner_nodes(scene, b.out, options.simplify, options.threads);
  start = stages.lap("inner", start);
  if (options.simplify)
    add_coarser_levels(scene, b.out, options.max_levels, whole, options.threads);
  stages.lap("levels", start);
  return std::move(b.out);
}

} // namespace irad
