#include "core/mesh/hierarchy/cluster_levels.h"

#include "core/mesh/local_vertices.h"
#include "core/util/parallel_rows.h"

#include "core/util/error.h"

#include <algorithm>
#include <atomic>
#include <limits>
#include <meshoptimizer.h>
#include <numeric>

namespace irad {

namespace {

// Relative error (of the mesh's extent) below which meshoptimizer's collapses count as exact.
constexpr float kExact = 1e-6f;

// meshoptimizer's error estimate of a step that simplifies the border too, times this: its
// estimate weighs a border's sag less than the surface's, and tests/test_shadow_lod.cpp measured
// the true distance up to 3.3 times it on the coarser levels of a sphere's regions (1.4 times
// with the border locked).
constexpr float kFreeBorderError = 2.5f;

// `input` simplified to 1/divisor of its triangles (divisor 0: as far as target_error, relative
// to the extent, allows), its open edges (the region's border) locked unless `border` is Free
// (then they simplify as a polyline within the error); error: this step's (world units).
struct Simplified {
  std::vector<std::uint32_t> indices;
  float error = 0.0f;
  bool exact = false; // every collapse within kExact of the extent
};
enum class Border { Locked, Free };
// local_of: a LocalMaps map, or nullptr (the input renumbered through a small hash table: the
// same numbers).
Simplified simplify_union(const Scene& scene, const std::vector<std::uint32_t>& input,
                          std::vector<std::uint32_t>* local_of, std::size_t divisor = 2,
                          float target_error = 1.0f, Border border = Border::Locked) {
  // A compact vertex array of the vertices used (meshoptimizer scales by all it is given).
  const LocalVertices v = local_of ? local_vertices(input, *local_of) : local_vertices(input);
  const std::vector<std::uint32_t>& local = v.local;
  std::vector<glm::vec3> positions(v.global.size());
  for (std::size_t l = 0; l < positions.size(); ++l) positions[l] = scene.positions[v.global[l]];
  Simplified s;
  std::vector<std::uint32_t> dest(input.size());
  const std::size_t target = divisor == 0 ? 0 : input.size() / (3 * divisor) * 3;
  float relative = 0.0f;
  const unsigned options = border == Border::Locked ? unsigned{meshopt_SimplifyLockBorder} : 0u;
  const std::size_t count =
      meshopt_simplify(dest.data(), local.data(), local.size(), &positions[0].x, positions.size(),
                       sizeof(glm::vec3), target, target_error, options, &relative);
  s.error = relative * meshopt_simplifyScale(&positions[0].x, positions.size(), sizeof(glm::vec3)) *
            (border == Border::Free ? kFreeBorderError : 1.0f);
  s.exact = relative <= kExact;
  s.indices.resize(count);
  for (std::size_t k = 0; k < count; ++k) s.indices[k] = v.global[dest[k]];
  return s;
}

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

// One node's coarser levels (add_coarser_levels), meshes one after another in `indices`.
struct NodeLevels {
  std::vector<ClusterLevel> levels; // first: offsets into `indices`
  std::vector<std::uint32_t> indices;
};

// A component root's levels start from the cut of its tree through the nodes of at most this
// height: their meshes, each about 2^-height of its region's triangles, are the whole
// component's at a quarter of the cost of simplifying the original triangles that far.
constexpr int kWholeCutHeight = 2;
// ... or through higher nodes where that cut would hold more triangles than this: a component of
// millions of triangles would otherwise quarter millions of triangles on one core (2.5M on the
// 10M terrain, about 2 s), for whole-component meshes finer than any shadow face draws of it.
// Measured (levels stage on 2 threads, two pairs in turn): the 10M terrain from height 4 (600k
// triangles) 5.00-5.40 s against 5.61-6.77 s, 14,355 shadow triangles per VPL and the image the
// same; zdm2, godot and both sphere boxes, whose cuts stay below it, keep their hierarchies. (A
// lower bound costs smaller scenes triangles: godot's cut from height 4 draws 5,726 per VPL
// against 4,990, the 2.1M sphere box's 1,019 against 986.)
constexpr std::size_t kWholeCutTriangles = std::size_t{1} << 20;

// The nodes of the cut below `root` through the nodes of height at most `top`, depth first.
std::vector<std::size_t> cut_nodes(const MeshClusters& out, std::size_t root,
                                   const std::vector<int>& height, int top) {
  std::vector<std::size_t> cut, stack{root};
  while (!stack.empty()) {
    const std::size_t n = stack.back();
    stack.pop_back();
    const ClusterNode& node = out.nodes[n];
    if (height[n] > top) {
      stack.push_back(static_cast<std::size_t>(node.children[1]));
      stack.push_back(static_cast<std::size_t>(node.children[0]));
    } else {
      cut.push_back(n);
    }
  }
  return cut;
}

// The meshes of the cut below `root` through the nodes of height at most kWholeCutHeight (or the
// least height above it whose cut holds at most kWholeCutTriangles), joined: one seamless mesh of
// the component (neighbouring regions share their locked borders); `error`: the largest of theirs.
std::vector<std::uint32_t> shallow_cut(const MeshClusters& out, std::size_t root,
                                       const std::vector<int>& height, float& error) {
  const auto indices = [&](const std::vector<std::size_t>& cut) {
    std::size_t count = 0;
    for (std::size_t n : cut) count += out.nodes[n].mesh_count;
    return count;
  };
  int top = kWholeCutHeight;
  std::vector<std::size_t> cut = cut_nodes(out, root, height, top);
  while (top < height[root] && indices(cut) > 3 * kWholeCutTriangles)
    cut = cut_nodes(out, root, height, ++top);
  std::vector<std::uint32_t> mesh;
  mesh.reserve(indices(cut));
  error = 0.0f;
  for (std::size_t n : cut) {
    const ClusterNode& node = out.nodes[n];
    mesh.insert(mesh.end(), out.indices.begin() + node.mesh_first,
                out.indices.begin() + node.mesh_first + node.mesh_count);
    error = std::max(error, node.error);
  }
  return mesh;
}

// Its mesh divided by `step` again and again while that removes at least a tenth of the
// triangles, its region's border simplified with it (the base meshes keep it exactly). A locked
// border would keep the original tessellation in every level, so that no level of a node could drop
// below its border's length in triangles: on a finely tessellated surface seen from near (a VPL on
// a terrain) the cut would be the borders of the nodes it holds, growing with the tessellation (the
// 2M-triangle terrain: 41,189 triangles per VPL locked, 13,263 free; docs/performance.md "Shadow
// maps against scene size"). Free, neighbouring regions drawn at different levels may leave a crack
// along their shared border, at most the two levels' errors wide, which the cut keeps below half a
// texel each. Where the first step needs no error (coplanar triangles: flat walls), that level goes
// on as far as collapses without error go. A first step with error means meshoptimizer, which
// collapses the cheapest edges first, ran out of exact ones before half: a pass for them alone
// would cost a simplification of the whole mesh for less (on the 2.1M sphere box: 43 % of the
// levels' time, and below a tenth of the triangles on 62 % of the nodes). A root of one connected
// component (`whole`) starts from the shallow cut of its tree instead and quarters it, the
// component's own open edges locked: a closed surface simplifies as far as its error allows.
// `mesh`: the node's, of error `error`; local_of as simplify_union's.
NodeLevels levels_of_mesh(const Scene& scene, std::vector<std::uint32_t> mesh, float error,
                          bool whole, int max_levels, int step,
                          std::vector<std::uint32_t>* local_of) {
  NodeLevels result;
  const Border border = whole ? Border::Locked : Border::Free;
  for (int steps = 0; steps < max_levels && !mesh.empty();) {
    Simplified s = simplify_union(scene, mesh, local_of, whole ? 4 : step, 1.0f, border);
    if (10 * s.indices.size() > 9 * mesh.size()) break;
    if (result.levels.empty() && s.exact) { // no error yet: as far as none takes it
      Simplified rest = simplify_union(scene, s.indices, local_of, 0, kExact, border);
      s.indices = std::move(rest.indices);
      s.error += rest.error;
    } else {
      ++steps;
    }
    error += s.error;
    mesh = std::move(s.indices);
    result.levels.push_back({error, static_cast<std::uint32_t>(result.indices.size()),
                             static_cast<std::uint32_t>(mesh.size())});
    result.indices.insert(result.indices.end(), mesh.begin(), mesh.end());
  }
  return result;
}

// Node n's levels (levels_of_mesh) from its mesh in out.indices, or for a component's root
// (`whole`) from its shallow cut.
NodeLevels coarser_levels(const Scene& scene, const MeshClusters& out, std::size_t n, bool whole,
                          int max_levels, int step, const std::vector<int>& height,
                          std::vector<std::uint32_t>& local_of) {
  const ClusterNode& node = out.nodes[n];
  float error = node.error;
  std::vector<std::uint32_t> mesh =
      whole ? shallow_cut(out, n, height, error)
            : std::vector<std::uint32_t>(out.indices.begin() + node.mesh_first,
                                         out.indices.begin() + node.mesh_first + node.mesh_count);
  return levels_of_mesh(scene, std::move(mesh), error, whole, max_levels, step, &local_of);
}

} // namespace

// The inner nodes' meshes, height by height (each height's nodes in parallel: a node reads only
// its children's meshes), then appended in node order: the same result on any number of threads.
void simplify_inner_nodes(const Scene& scene, MeshClusters& out, bool simplify, unsigned threads) {
  std::vector<std::vector<std::uint32_t>> meshes(out.nodes.size());
  LocalMaps local(scene.positions.size(),
                  worker_count(threads, static_cast<int>(out.nodes.size())));
  // Appends node n's mesh (a leaf's from the original part, an inner node's from `meshes`).
  const auto append_mesh = [&](std::int32_t n, std::vector<std::uint32_t>& into) {
    const ClusterNode& c = out.nodes[static_cast<std::size_t>(n)];
    if (c.leaf()) {
      into.insert(into.end(), out.indices.begin() + c.mesh_first,
                  out.indices.begin() + c.mesh_first + c.mesh_count);
    } else {
      const std::vector<std::uint32_t>& m = meshes[static_cast<std::size_t>(n)];
      into.insert(into.end(), m.begin(), m.end());
    }
  };
  const auto simplify_node = [&](std::size_t n, unsigned worker) {
    ClusterNode& node = out.nodes[n];
    std::vector<std::uint32_t> input;
    append_mesh(node.children[0], input);
    append_mesh(node.children[1], input);
    const float below = std::max(out.nodes[static_cast<std::size_t>(node.children[0])].error,
                                 out.nodes[static_cast<std::size_t>(node.children[1])].error);
    node.error = below;
    if (simplify && !input.empty()) {
      Simplified s = simplify_union(scene, input, &local.of(worker));
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
  std::size_t total = out.indices.size(); // reserved at once: no copy of a half-grown array
  for (const std::vector<std::uint32_t>& m : meshes) total += m.size();
  out.indices.reserve(total);
  for (std::size_t n = 0; n < out.nodes.size(); ++n) {
    ClusterNode& node = out.nodes[n];
    if (node.leaf()) continue;
    node.mesh_first = static_cast<std::uint32_t>(out.indices.size());
    node.mesh_count = static_cast<std::uint32_t>(meshes[n].size());
    out.indices.insert(out.indices.end(), meshes[n].begin(), meshes[n].end());
    meshes[n] = {};
  }
}

// Every node's coarser levels, in parallel (the component roots first: the longest tasks), then
// appended in node order: the same result on any number of threads (deferred: which nodes are
// built beside the roots' tasks depends on the timing; their levels do not).
void add_coarser_levels(const Scene& scene, MeshClusters& out, int max_levels, int step,
                        const std::vector<bool>& whole, bool leaf_levels, bool defer,
                        unsigned threads) {
  const std::vector<int> height = node_heights(out);
  std::vector<std::size_t> order; // the component roots first, then the rest from the top down
  order.reserve(out.nodes.size());
  for (std::size_t n = 0; n < out.nodes.size(); ++n)
    if (leaf_levels || whole[n] || !out.nodes[n].leaf()) order.push_back(n);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return whole[a] != whole[b] ? bool(whole[a]) : height[a] > height[b];
  });
  // Deferred: a node other than a root is built only while a root's task still runs (on a core
  // that would otherwise wait for it); the rest stay pending.
  std::atomic<std::size_t> roots_left = static_cast<std::size_t>(
      std::count_if(order.begin(), order.end(), [&](std::size_t n) { return whole[n]; }));
  std::vector<NodeLevels> levels(out.nodes.size());
  LocalMaps local(scene.positions.size(), worker_count(threads, static_cast<int>(order.size())));
  std::vector<char> pending(out.nodes.size(), 0); // written by the task of its node alone
  parallel_tasks(static_cast<int>(order.size()), threads, [&](int k, unsigned worker) {
    const std::size_t n = order[static_cast<std::size_t>(k)];
    if (defer && !whole[n] && roots_left.load() == 0) {
      pending[n] = 1;
      return;
    }
    levels[n] = coarser_levels(scene, out, n, whole[n], max_levels, step, height, local.of(worker));
    if (whole[n]) --roots_left;
  });
  std::size_t total = out.indices.size(), count = 0; // reserved at once, as above
  for (const NodeLevels& l : levels) {
    total += l.indices.size();
    count += l.levels.size();
  }
  out.indices.reserve(total);
  out.levels.reserve(count);
  for (std::size_t n = 0; n < out.nodes.size(); ++n) {
    ClusterNode& node = out.nodes[n];
    if (pending[n]) {
      node.levels_first = ClusterNode::kPendingLevels;
      node.levels_count = 0;
      out.deferred_max_levels = max_levels;
      out.deferred_step = step;
      continue;
    }
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

void add_deferred_levels(const Scene& scene, MeshClusters& c, std::vector<std::int32_t> nodes,
                         unsigned threads) {
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  std::erase_if(nodes, [&](std::int32_t n) {
    return n < 0 || static_cast<std::size_t>(n) >= c.nodes.size() ||
           !c.nodes[static_cast<std::size_t>(n)].levels_pending();
  });
  if (nodes.empty()) return;
  std::vector<NodeLevels> levels(nodes.size());
  parallel_tasks(static_cast<int>(nodes.size()), threads, [&](int k, unsigned) {
    const ClusterNode& node = c.nodes[static_cast<std::size_t>(nodes[static_cast<std::size_t>(k)])];
    std::vector<std::uint32_t> mesh(node.mesh_count);
    if (c.stored_indices)
      c.stored_indices->copy_range(node.mesh_first, node.mesh_count, mesh.data());
    else
      std::copy_n(c.indices.begin() + node.mesh_first, node.mesh_count, mesh.begin());
    levels[static_cast<std::size_t>(k)] = levels_of_mesh(
        scene, std::move(mesh), node.error, false, c.deferred_max_levels, c.deferred_step, nullptr);
  });
  // This call's indices from a multiple of kLateAlign of the index space.
  c.late_indices.resize((c.late_indices.size() + kLateAlign - 1) / kLateAlign * kLateAlign);
  std::size_t added = 0;
  for (const NodeLevels& l : levels) added += l.indices.size();
  if (c.late_base() + c.late_indices.size() + added > std::numeric_limits<std::uint32_t>::max())
    throw Error("", "shadow hierarchy", "levels past 2^32 indices");
  c.late_indices.reserve(c.late_indices.size() + added);
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    ClusterNode& node = c.nodes[static_cast<std::size_t>(nodes[k])];
    c.late_nodes.push_back(nodes[k]);
    node.levels_first = static_cast<std::uint32_t>(c.levels.size());
    node.levels_count = static_cast<std::uint32_t>(levels[k].levels.size());
    const std::size_t base = c.late_base() + c.late_indices.size();
    for (ClusterLevel level : levels[k].levels) {
      level.first += static_cast<std::uint32_t>(base);
      c.levels.push_back(level);
    }
    c.late_indices.insert(c.late_indices.end(), levels[k].indices.begin(), levels[k].indices.end());
  }
}

} // namespace irad
