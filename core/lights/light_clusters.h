#pragma once
// Many VPLs through few shadow maps: matrix row-column sampling (Hasan, Pellacini & Bala 2007).
// The image is the product of a light matrix, A_ij = the radiance VPL j reflects at pixel i. A
// reduced matrix R (r sampled pixels' rows, computed exactly: walk/vpls/light_rows.h) tells which
// columns (VPLs) look alike; they are clustered, and each cluster C is drawn as one
// representative j in C, chosen with probability alpha_j / alpha_C and scaled by
// alpha_C / alpha_j, alpha_j = |R_j| the norm of its reduced column, alpha_C = sum_C alpha_j:
//   E[representative of C] = sum_{j in C} (alpha_j / alpha_C) (alpha_C / alpha_j) I_j = sum_C I_j,
// so the c representatives are an unbiased estimate of all the VPLs' light at every pixel (a
// Lambertian column no sampled row sees, alpha_j = 0, is dropped: the one bias, its share of the
// power is reported; glossy ones are kept, pick_representatives). The clustering minimises Hasan's
// cost of a cluster,
//   cost(C) = sum_{i, j in C} alpha_i alpha_j |x_i - x_j|^2 = 2 (alpha_C^2 - |sum_C R_j|^2),
// x_j = R_j / alpha_j, by splitting the costliest cluster along a random line (through two
// columns drawn by norm) at the point of least total cost, until there are c.
#include "core/lights/vpl.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace irad {

// The reduced light matrix: `rows` luminances per column (VPL), column-major.
struct ReducedMatrix {
  std::size_t rows = 0;
  std::size_t columns = 0;
  std::vector<float> values; // column j at [j * rows, (j + 1) * rows)

  const float* column(std::size_t j) const { return values.data() + j * rows; }
  float* column(std::size_t j) { return values.data() + j * rows; }
};

// Scales every row by 1 / (its total + a floor), so that dark pixels weigh as much as bright
// ones: the clustering then aims at the relative error. Any positive row weights keep the
// representatives unbiased. floor: relative to the mean row total (rows of no light stay 0).
void weight_rows_by_inverse_total(ReducedMatrix& m, float floor = 0.05f);

// Clusters as ranges of a permutation of the columns with a positive norm.
struct ColumnClusters {
  std::vector<std::uint32_t> order;  // column indices, cluster by cluster
  std::vector<std::uint32_t> starts; // cluster k: order[starts[k], starts[k + 1])
  std::vector<float> norms;          // alpha_j of every column (0: seen by no row)
  std::size_t clusters() const { return starts.empty() ? 0 : starts.size() - 1; }
};

// At most `clusters` clusters of the columns with alpha_j > 0; fewer when there are fewer such
// columns or when every cluster left has cost 0. Deterministic for a seed, whatever the number
// of threads (0: all cores).
ColumnClusters cluster_columns(const ReducedMatrix& m, std::size_t clusters, std::uint64_t seed,
                               unsigned threads = 0);

struct Representatives {
  VplSet set;                    // the walk's set with one scaled VPL per cluster
  double dropped_fraction = 0.0; // share of the VPLs' summed intensity no row saw (Lambertian)
};

// One representative per cluster (drawn with the seed), its intensity scaled by
// alpha_C / alpha_j; the set keeps the walk's counts and mirrors, not its clamp field (the
// representatives are clamped anew at their own density). In a cluster with glossy VPLs each
// glossy one's weight is alpha_j plus half its power's share of alpha_C (a lobe may light what no
// sampled row sees), and the scale is the weights' sum over its weight: still unbiased. Glossy
// VPLs no row sees at all are not dropped: their power's share of the representatives (at least
// one) is drawn from them by power and appended (more representatives than clusters).
Representatives pick_representatives(const VplSet& walk, const ColumnClusters& clusters,
                                     std::uint64_t seed);

} // namespace irad
