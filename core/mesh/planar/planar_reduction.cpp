#include "core/mesh/planar/planar_reduction.h"

#include "core/mesh/planar/vertex_fans.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/glm.hpp>
#include <numeric>
#include <span>

namespace irad {

namespace {

using glm::dvec3;
constexpr std::uint32_t kNone = ~0u;
// A changed triangle must keep twice its projected area above this times its longest edge
// squared (about the sine of its smallest angle): exactly degenerate fans are refused.
constexpr double kMinSine = 1e-6;

enum class Role : std::uint8_t { Locked, Interior, Line };

// One edge v-x of v's fan: how many fan triangles hold it, in which directions, which patches.
struct FanEdge {
  std::uint32_t x = kNone;
  int count = 0, out = 0;  // triangles with the edge, of them those running v -> x
  std::uint32_t t[2] = {}; // the first two
};

// Each vertex's alive triangles, in one array: a vertex's list is a run of it with room to grow,
// and a list that outgrows its room moves to the end with twice the room. (A vector per vertex
// costs an allocation each: a quarter of the reduction's time on a million vertices.) Lists keep
// the order a vector's push_back and swap-with-last removal give.
class Fans {
public:
  // Every alive triangle in the lists of its three vertices, in ascending order.
  Fans(const std::vector<glm::uvec3>& tris, const std::vector<bool>& alive, std::size_t vertices) {
    VertexFans all(
        tris, vertices, [&](std::uint32_t t) { return static_cast<bool>(alive[t]); },
        [](std::uint32_t) { return true; });
    size_.resize(vertices);
    for (std::size_t v = 0; v < vertices; ++v) size_[v] = all.first[v + 1] - all.first[v];
    room_ = size_;
    all.first.pop_back();
    first_ = std::move(all.first);
    list_ = std::move(all.list);
  }
  std::span<const std::uint32_t> operator[](std::uint32_t v) const {
    return {list_.data() + first_[v], size_[v]};
  }
  void push(std::uint32_t v, std::uint32_t t) {
    if (size_[v] == room_[v]) move_to_end(v);
    list_[first_[v] + size_[v]++] = t;
  }
  // Removes t (which v's list holds), the last one taking its place.
  void drop(std::uint32_t v, std::uint32_t t) {
    std::uint32_t* f = list_.data() + first_[v];
    *std::find(f, f + size_[v], t) = f[size_[v] - 1];
    --size_[v];
  }
  void clear(std::uint32_t v) { size_[v] = 0; }

private:
  void move_to_end(std::uint32_t v) {
    const auto at = static_cast<std::uint32_t>(list_.size());
    room_[v] = std::max<std::uint32_t>(4, 2 * room_[v]);
    list_.resize(list_.size() + room_[v]);
    std::copy_n(list_.begin() + first_[v], size_[v], list_.begin() + at);
    first_[v] = at;
  }

  std::vector<std::uint32_t> first_, size_, room_, list_;
};

struct Reducer {
  const std::vector<glm::vec3>& positions;
  float epsilon;
  std::vector<glm::uvec3> tris;
  std::vector<bool> alive;
  std::vector<std::uint32_t> patch; // per triangle
  std::vector<dvec3> normals;       // per patch, unit
  Fans fan;                         // per vertex: its alive triangles
  std::vector<Role> role;
  std::vector<std::array<std::uint32_t, 2>> chain; // a Line vertex's neighbours on its chain
  std::vector<std::uint32_t> stamp;                // per vertex, for set tests
  std::uint32_t clock = 0;
  std::vector<std::uint32_t> common, third, targets; // scratch of can_collapse and run
  std::vector<std::uint32_t> collapsing;             // scratch of collapse
  mutable std::vector<std::pair<std::uint32_t, std::uint32_t>> edge_ends; // scratch of fan_edges
  mutable std::vector<std::uint32_t> piece;                               // scratch of one_piece

  Reducer(const std::vector<glm::vec3>& p, float e, const std::vector<glm::uvec3>& t,
          std::vector<bool> a, Fans f)
      : positions(p), epsilon(e), tris(t), alive(std::move(a)), fan(std::move(f)) {}

  dvec3 p(std::uint32_t v) const { return dvec3(positions[v]); }
  dvec3 cross_of(const glm::uvec3& t) const { return glm::cross(p(t.y) - p(t.x), p(t.z) - p(t.x)); }

  // The fan's edges of v, sorted by x, into `out`.
  void fan_edges(std::uint32_t v, std::vector<FanEdge>& out) const {
    edge_ends.clear(); // (x, triangle * 2 + out)
    for (std::uint32_t t : fan[v]) {
      const glm::uvec3& tri = tris[t];
      const int i = tri.x == v ? 0 : tri.y == v ? 1 : 2;
      edge_ends.push_back({tri[(i + 1) % 3], 2 * t + 1});
      edge_ends.push_back({tri[(i + 2) % 3], 2 * t});
    }
    std::sort(edge_ends.begin(), edge_ends.end());
    out.clear();
    FanEdge e; // counted here, pushed when the next edge begins, rather than counted in place
               // in `out` (1.50-1.57 s against 1.55-1.63 s for the reduction of the 10M sphere
               // box, 3 runs each in turn)
    for (const auto& [x, code] : edge_ends) {
      if (e.count > 0 && e.x != x) {
        out.push_back(e);
        e = {};
      }
      e.x = x;
      if (e.count < 2) e.t[e.count] = code / 2;
      ++e.count;
      e.out += static_cast<int>(code & 1u);
    }
    if (e.count > 0) out.push_back(e);
  }

  bool feature(const FanEdge& e) const { return e.count == 1 || patch[e.t[0]] != patch[e.t[1]]; }

  // Whether v's fan triangles form one piece through their shared edges.
  bool one_piece(std::uint32_t v, const std::vector<FanEdge>& edges) const {
    const std::span<const std::uint32_t> f = fan[v];
    piece.resize(f.size());
    std::iota(piece.begin(), piece.end(), 0u);
    const auto slot = [&](std::uint32_t t) {
      return static_cast<std::uint32_t>(std::find(f.begin(), f.end(), t) - f.begin());
    };
    const auto find = [&](std::uint32_t a) {
      while (piece[a] != a) a = piece[a] = piece[piece[a]];
      return a;
    };
    std::size_t pieces = f.size();
    for (const FanEdge& e : edges) {
      if (e.count != 2) continue;
      const std::uint32_t a = find(slot(e.t[0])), b = find(slot(e.t[1]));
      if (a != b) {
        piece[a] = b;
        --pieces;
      }
    }
    return pieces == 1;
  }

  // The distance of q from the line through a and b.
  double off_line(const dvec3& q, const dvec3& a, const dvec3& b) const {
    const dvec3 d = b - a;
    return glm::length(glm::cross(q - a, d)) / glm::length(d);
  }

  void grow_patches();
  void classify(const std::vector<bool>& locked);
  void straighten_chains();
  bool can_collapse(std::uint32_t v, std::uint32_t u);
  void collapse(std::uint32_t v, std::uint32_t u);
  std::size_t run();
};

void Reducer::grow_patches() {
  std::vector<double> area(tris.size());
  for (std::size_t t = 0; t < tris.size(); ++t) area[t] = glm::length(cross_of(tris[t]));
  // Seeds by octave of area, the largest first, each octave's in triangle order: a mesh's order
  // keeps neighbours near in memory, where an exact sort by area would visit a curved surface's
  // nearly equal triangles in an order with no locality (a cache miss for every neighbour).
  // Placed by counting (a few dozen octaves): the order of a sort by (-octave, t).
  std::vector<int> octave(tris.size());
  int lowest = 0, highest = 0;
  for (std::uint32_t t = 0; t < tris.size(); ++t) {
    std::frexp(area[t], &octave[t]);
    lowest = t == 0 ? octave[t] : std::min(lowest, octave[t]);
    highest = t == 0 ? octave[t] : std::max(highest, octave[t]);
  }
  std::vector<std::uint32_t> next(static_cast<std::size_t>(highest - lowest) + 2, 0);
  for (const int o : octave) ++next[static_cast<std::size_t>(highest - o) + 1];
  std::partial_sum(next.begin(), next.end(), next.begin());
  std::vector<std::uint32_t> seeds(tris.size());
  for (std::uint32_t t = 0; t < tris.size(); ++t)
    seeds[next[static_cast<std::size_t>(highest - octave[t])]++] = t;
  octave = {};
  patch.assign(tris.size(), kNone);
  std::vector<std::uint32_t> queue;
  for (std::uint32_t seed : seeds) {
    if (!alive[seed] || patch[seed] != kNone) continue;
    const auto id = static_cast<std::uint32_t>(normals.size());
    const dvec3 n = cross_of(tris[seed]) / area[seed];
    const double d = glm::dot(n, p(tris[seed].x));
    normals.push_back(n);
    const auto joins = [&](std::uint32_t t) {
      if (!alive[t] || patch[t] != kNone || !(glm::dot(cross_of(tris[t]), n) > 0.0)) return false;
      for (int c = 0; c < 3; ++c)
        if (std::abs(glm::dot(n, p(tris[t][c])) - d) > epsilon) return false;
      return true;
    };
    patch[seed] = id;
    queue.assign(1, seed);
    while (!queue.empty()) {
      const glm::uvec3 t = tris[queue.back()];
      queue.pop_back();
      for (int e = 0; e < 3; ++e) {
        const std::uint32_t a = t[e], b = t[(e + 1) % 3];
        for (std::uint32_t s : fan[a]) {
          const glm::uvec3& o = tris[s];
          if ((o.x == b || o.y == b || o.z == b) && joins(s)) {
            patch[s] = id;
            queue.push_back(s);
          }
        }
      }
    }
  }
}

void Reducer::classify(const std::vector<bool>& locked) {
  role.assign(positions.size(), Role::Locked);
  chain.assign(positions.size(), {kNone, kNone});
  std::vector<FanEdge> edges;
  std::vector<std::uint32_t> features;
  for (std::uint32_t v = 0; v < positions.size(); ++v) {
    if (fan[v].empty() || (!locked.empty() && locked[v])) continue;
    fan_edges(v, edges);
    features.clear();
    bool sound = true;
    for (const FanEdge& e : edges) {
      // Non-manifold or inconsistently wound: left as it is.
      if (e.count > 2 || (e.count == 2 && e.out != 1)) sound = false;
      if (feature(e)) features.push_back(e.x);
    }
    if (!sound || !one_piece(v, edges)) continue;
    if (features.empty()) {
      role[v] = Role::Interior;
    } else if (features.size() == 2) {
      const dvec3 a = p(features[0]), b = p(features[1]), q = p(v);
      const double along = glm::dot(q - a, b - a);
      if (along > 0.0 && along < glm::dot(b - a, b - a) && off_line(q, a, b) <= epsilon) {
        role[v] = Role::Line;
        chain[v] = {features[0], features[1]};
      }
    }
  }
}

// A chain of Line vertices between two other vertices A and B stays collapsible only if each of
// its vertices lies within epsilon of the line AB: then whatever the collapses leave of it
// stays within epsilon of every vertex it removed (a slowly curving outline is kept).
void Reducer::straighten_chains() {
  std::vector<std::uint32_t> parent(positions.size());
  std::iota(parent.begin(), parent.end(), 0u);
  const auto find = [&](std::uint32_t a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  };
  for (std::uint32_t v = 0; v < positions.size(); ++v)
    if (role[v] == Role::Line)
      for (std::uint32_t x : chain[v])
        if (role[x] == Role::Line) parent[find(x)] = find(v);
  struct Ends {
    std::uint32_t a = kNone, b = kNone;
    int count = 0;
    bool straight = true;
  };
  std::vector<Ends> ends(positions.size());
  for (std::uint32_t v = 0; v < positions.size(); ++v) {
    if (role[v] != Role::Line) continue;
    Ends& e = ends[find(v)];
    for (std::uint32_t x : chain[v]) {
      if (role[x] == Role::Line) continue;
      (e.count == 0 ? e.a : e.b) = x;
      ++e.count;
    }
  }
  for (std::uint32_t v = 0; v < positions.size(); ++v) {
    if (role[v] != Role::Line) continue;
    Ends& e = ends[find(v)];
    if (e.count != 2 || e.a == e.b || off_line(p(v), p(e.a), p(e.b)) > epsilon) e.straight = false;
  }
  for (std::uint32_t v = 0; v < positions.size(); ++v)
    if (role[v] == Role::Line && !ends[find(v)].straight) role[v] = Role::Locked;
}

// The link condition (the vertices next to both v and u are exactly the third vertices of the
// triangles on edge v-u) and every changed triangle still facing its patch's way.
bool Reducer::can_collapse(std::uint32_t v, std::uint32_t u) {
  ++clock;
  for (std::uint32_t t : fan[u])
    for (int c = 0; c < 3; ++c) stamp[tris[t][c]] = clock;
  common.clear();
  third.clear();
  for (std::uint32_t t : fan[v]) {
    const glm::uvec3& tri = tris[t];
    const bool on_edge = tri.x == u || tri.y == u || tri.z == u;
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t x = tri[c];
      if (x == v || x == u) continue;
      if (stamp[x] == clock) common.push_back(x);
      if (on_edge) third.push_back(x);
    }
    if (on_edge) continue;
    glm::uvec3 moved = tri;
    for (int c = 0; c < 3; ++c)
      if (moved[c] == v) moved[c] = u;
    const dvec3 a = p(moved.x), b = p(moved.y), c = p(moved.z);
    const double longest =
        std::max({glm::dot(b - a, b - a), glm::dot(c - b, c - b), glm::dot(a - c, a - c)});
    if (!(glm::dot(glm::cross(b - a, c - a), normals[patch[t]]) > kMinSine * longest)) return false;
  }
  std::sort(common.begin(), common.end());
  common.erase(std::unique(common.begin(), common.end()), common.end());
  std::sort(third.begin(), third.end());
  third.erase(std::unique(third.begin(), third.end()), third.end());
  return !third.empty() && common == third;
}

void Reducer::collapse(std::uint32_t v, std::uint32_t u) {
  const std::span<const std::uint32_t> around = fan[v];
  collapsing.assign(around.begin(), around.end()); // fan.push may move the lists
  for (std::uint32_t t : collapsing) {
    glm::uvec3& tri = tris[t];
    if (tri.x == u || tri.y == u || tri.z == u) {
      alive[t] = false;
      for (int c = 0; c < 3; ++c)
        if (tri[c] != v) fan.drop(tri[c], t);
      continue;
    }
    for (int c = 0; c < 3; ++c)
      if (tri[c] == v) tri[c] = u;
    fan.push(u, t);
  }
  fan.clear(v);
  if (role[v] == Role::Line) { // u and the chain's other neighbour w now meet
    const std::uint32_t w = chain[v][0] == u ? chain[v][1] : chain[v][0];
    for (std::uint32_t x : {u, w})
      if (role[x] == Role::Line)
        for (std::uint32_t& y : chain[x])
          if (y == v) y = x == u ? w : u;
  }
}

// Passes over the collapsible vertices, the shortest valid edge of each; a vertex next to a
// collapse waits for the next pass (the collapses of one pass are independent, so fans grow
// slowly instead of into one hub). Until a pass collapses nothing.
std::size_t Reducer::run() {
  std::vector<std::uint32_t> active;
  for (std::uint32_t v = 0; v < positions.size(); ++v)
    if (role[v] != Role::Locked) active.push_back(v);
  std::vector<std::uint32_t> waits(positions.size(), 0);
  std::size_t collapses = 0;
  for (std::uint32_t pass = 1;; ++pass) {
    std::size_t made = 0, kept = 0;
    for (std::uint32_t v : active) {
      if (waits[v] == pass) {
        active[kept++] = v;
        continue;
      }
      targets.clear();
      if (role[v] == Role::Line) {
        targets.assign(chain[v].begin(), chain[v].end());
      } else {
        for (std::uint32_t t : fan[v])
          for (int c = 0; c < 3; ++c)
            if (tris[t][c] != v) targets.push_back(tris[t][c]);
        std::sort(targets.begin(), targets.end());
        targets.erase(std::unique(targets.begin(), targets.end()), targets.end());
      }
      const dvec3 q = p(v);
      std::sort(targets.begin(), targets.end(), [&](std::uint32_t a, std::uint32_t b) {
        const double da = glm::dot(p(a) - q, p(a) - q), db = glm::dot(p(b) - q, p(b) - q);
        return da != db ? da < db : a < b;
      });
      bool done = false;
      for (std::uint32_t u : targets) {
        if (!can_collapse(v, u)) continue;
        for (std::uint32_t t : fan[v])
          for (int c = 0; c < 3; ++c) waits[tris[t][c]] = pass;
        collapse(v, u);
        done = true;
        break;
      }
      if (done) {
        ++made;
      } else {
        active[kept++] = v;
      }
    }
    active.resize(kept);
    collapses += made;
    if (made == 0) break;
  }
  return collapses;
}

} // namespace

PlanarReduction reduce_planar(const std::vector<glm::vec3>& positions,
                              const std::vector<glm::uvec3>& triangles, float epsilon,
                              const std::vector<bool>& locked) {
  std::vector<bool> alive(triangles.size(), true);
  for (std::uint32_t t = 0; t < triangles.size(); ++t) {
    const glm::uvec3& tri = triangles[t];
    alive[t] = !(tri.x == tri.y || tri.y == tri.z || tri.z == tri.x ||
                 glm::cross(dvec3(positions[tri.y]) - dvec3(positions[tri.x]),
                            dvec3(positions[tri.z]) - dvec3(positions[tri.x])) == dvec3(0.0));
  }
  Fans fans(triangles, alive, positions.size());
  Reducer r(positions, epsilon, triangles, std::move(alive), std::move(fans));
  r.grow_patches();
  r.classify(locked);
  r.straighten_chains();
  r.stamp.assign(positions.size(), 0);
  PlanarReduction out;
  out.patches = r.normals.size();
  out.collapses = r.run();
  for (std::size_t t = 0; t < r.tris.size(); ++t)
    if (r.alive[t]) out.triangles.push_back(r.tris[t]);
  return out;
}

} // namespace irad
