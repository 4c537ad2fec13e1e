#include "walk/vpls/vpl_clustering.h"

#include "core/lights/clamp_field.h"
#include "walk/vpls/light_rows.h"

namespace irad {

Representatives cluster_vpls(const Scene& scene, const RayScene& rays, const View& view,
                             const VplSet& walk, const VplClusteringOptions& options) {
  ReducedMatrix m =
      light_rows(scene, rays, view, walk,
                 {options.rows, options.clamp, options.seed, options.threads, options.cancel});
  weight_rows_by_inverse_total(m);
  const ColumnClusters clusters =
      cluster_columns(m, options.clusters, options.seed, options.threads);
  Representatives reps = pick_representatives(walk, clusters, options.seed);
  if (options.local_clamp)
    apply_local_clamp(reps.set, scene.bounds.diagonal(),
                      {options.clamp_neighbours, options.clamp_scale, options.clamp});
  return reps;
}

} // namespace irad
