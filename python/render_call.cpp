#include "render_call.h"

#include "arrays.h"
#include "core/sampling/sequence.h"
#include "core/util/error.h"
#include "core/util/log.h"
#include "irad/render.h"
#include "walk/rays/ray_scene.h"

#include <fmt/format.h>
#include <pybind11/stl.h>

namespace py = pybind11;

namespace irad::python {

namespace {

GlBackend backend(const std::string& name) {
  if (name == "auto") return GlBackend::Auto;
  if (name == "egl") return GlBackend::Egl;
  if (name == "osmesa") return GlBackend::OsMesa;
  throw Error("", "gl", "'" + name + "' is not auto, egl or osmesa");
}

std::pair<int, int> checked_size(std::pair<int, int> size) {
  const auto [w, h] = size;
  if (w < 1 || h < 1 || w > 16384 || h > 16384)
    throw Error("", "size", fmt::format("({}, {}) is out of range (1..16384 per side)", w, h));
  return size;
}

// interleave_edges: auto, traced, shaded or off (lib/irad/render.h set_edge_pixels).
void set_edges(const std::string& name, RenderOptions& o) {
  if (!set_edge_pixels(name, o))
    throw Error("", "interleave_edges", "'" + name + "' is not auto, traced, shaded or off");
}

void require_at_least_one(std::uint32_t value, const char* what) {
  if (value == 0) throw Error("", what, "must be at least 1");
}

RenderOptions render_options(const RenderKeywords& k) {
  RenderOptions o;
  o.estimator = parse_estimator(k.estimator);
  if (k.size) o.size = checked_size(*k.size);
  o.camera = k.camera;
  if (k.paths) require_at_least_one(*k.paths, "paths");
  require_at_least_one(k.spp, "spp");
  o.auto_paths = !k.paths;
  o.walk.paths = k.paths.value_or(o.walk.paths);
  o.walk.sequence = parse_sequence(k.sequence);
  o.walk.seed = k.seed;
  o.raster.clamp = k.clamp;
  o.raster.interleave = k.interleave.value_or(0); // 0: automatic (lib/irad/render.h)
  o.raster.batch = k.batch;
  o.raster.shadow_resolution = k.shadow_res;
  o.raster.jitter = k.jitter;
  o.raster.backend = backend(k.gl);
  o.pt.spp = k.spp;
  o.pt.seed = k.seed;
  o.pt.threads = k.threads;
  o.pt.pixel_footprint = k.jitter;
  o.bias_compensation = k.bias_compensation;
  o.auto_clusters = !k.clusters;
  set_edges(k.interleave_edges, o);
  if (k.visibility == "auto" || k.visibility == "maps" || k.visibility == "rays")
    o.raster.visibility = k.visibility == "auto"   ? Visibility::Auto
                          : k.visibility == "maps" ? Visibility::Maps
                                                   : Visibility::Rays;
  else
    throw Error("", "visibility", "'" + k.visibility + "' is not auto, maps or rays");
  o.clusters = k.clusters.value_or(0);
  require_at_least_one(k.rounds, "rounds");
  o.rounds = k.rounds;
  if (!(k.traced_roughness >= 0.0f && k.traced_roughness <= 1.0f))
    throw Error("", "traced_roughness", "must be between 0 and 1");
  o.traced_roughness = k.traced_roughness;
  require_at_least_one(k.glossy_samples, "glossy_samples");
  o.glossy_samples = k.glossy_samples;
  return o;
}

// One-time stages as (name, seconds) tuples, in the order they ran.
py::list stage_list(const std::vector<std::pair<std::string, double>>& stages) {
  py::list out;
  for (const auto& [name, seconds] : stages) out.append(py::make_tuple(name, seconds));
  return out;
}

py::dict stats_dict(const RenderKeywords& k, const RenderResult& r) {
  py::dict seconds;
  seconds["load"] = r.seconds.load;
  seconds["walk"] = r.seconds.walk;
  seconds["cluster"] = r.seconds.cluster;
  seconds["raster"] = r.seconds.raster;
  seconds["visibility"] = r.seconds.visibility;
  seconds["trace"] = r.seconds.trace;
  seconds["glossy"] = r.seconds.glossy;
  seconds["total"] = r.seconds.total;
  seconds["raster_setup"] = stage_list(r.seconds.raster_setup);
  seconds["hierarchy_beside"] = stage_list(r.seconds.hierarchy_beside);
  py::dict s;
  s["estimator"] = k.estimator;
  s["size"] = py::make_tuple(r.view.width, r.view.height);
  s["camera"] = r.camera.name;
  s["vpls"] = r.vpls.vpls.size();
  s["walk_vpls"] = r.walk_vpls;
  s["clusters"] = r.clusters; // as drawn: auto resolved
  s["interleave"] = r.interleave;
  s["interleave_edges"] = r.edge_mode;
  s["edge_pixels"] = r.edge_pixels;
  s["unsure_pixels"] = r.unsure_pixels;
  s["visibility"] = r.visibility; // raster, as drawn: auto resolved
  s["rounds"] = r.rounds;
  s["paths"] = r.vpls.paths;
  s["rho_bar"] = r.vpls.rho_bar;
  s["l_max"] = r.vpls.l_max;
  s["passes"] = r.passes;
  s["gl"] = r.gl;
  s["hierarchy_cache"] = r.hierarchy_cache;
  s["wall_cache"] = r.wall_cache;
  s["shadow_planes"] = r.shadow_planes;
  s["thinnest_wall"] = r.thinnest_wall;
  s["shadow_triangles"] = r.shadow_triangles;
  py::dict levels;
  levels["built"] = r.shadow_levels.built;
  levels["read"] = r.shadow_levels.read;
  levels["seconds"] = r.shadow_levels.seconds;
  s["shadow_levels"] = levels;
  py::dict gpu;
  gpu["scene"] = r.gpu_bytes.scene;
  gpu["shadow_pages"] = r.gpu_bytes.shadow_pages;
  gpu["camera_pages"] = r.gpu_bytes.camera_pages;
  s["gpu_bytes"] = gpu;
  s["seconds"] = seconds;
  return s;
}

// Asked by irad::render on the rendering thread between stages and passes: Python's signal
// handlers run (in the main thread), and a KeyboardInterrupt they raise cancels the render.
struct Interrupt {
  bool raised = false;
  bool operator()() {
    if (raised) return true;
    py::gil_scoped_acquire gil;
    raised = PyErr_CheckSignals() != 0; // the exception stays set for error_already_set
    return raised;
  }
};

} // namespace

py::tuple render(const Scene& scene, const RenderKeywords& keywords) {
  RenderOptions options = render_options(keywords);
  Interrupt interrupt;
  options.cancel_requested = std::ref(interrupt);
  RenderResult r;
  {
    py::gil_scoped_release released;
    Log log; // warnings on stderr, as the CLI writes them
    if (keywords.time) {
      Scene posed = scene;
      pose_at(posed, *keywords.time, log);
      r = irad::render(posed, options, log);
    } else {
      r = irad::render(scene, options, log);
    }
  }
  if (interrupt.raised) throw py::error_already_set();
  return py::make_tuple(to_array(r.image, 3), stats_dict(keywords, r));
}

namespace {

py::array vec3_column(const std::vector<Vpl>& vpls, glm::vec3 Vpl::*member) {
  FloatArray column({static_cast<py::ssize_t>(vpls.size()), py::ssize_t(3)});
  auto out = column.mutable_unchecked<2>();
  for (std::size_t i = 0; i < vpls.size(); ++i)
    for (int c = 0; c < 3; ++c) out(static_cast<py::ssize_t>(i), c) = (vpls[i].*member)[c];
  return column;
}

template <typename T, typename Member>
py::array column(const std::vector<Vpl>& vpls, Member m) {
  py::array_t<T> column(static_cast<py::ssize_t>(vpls.size()));
  auto out = column.template mutable_unchecked<1>();
  for (std::size_t i = 0; i < vpls.size(); ++i)
    out(static_cast<py::ssize_t>(i)) = static_cast<T>(m(vpls[i]));
  return column;
}

py::array vpl_array(const std::vector<Vpl>& vpls) {
  const py::module_ np = py::module_::import("numpy");
  py::list fields;
  for (const char* name : {"position", "normal", "intensity"})
    fields.append(py::make_tuple(name, "<f4", py::make_tuple(3)));
  fields.append(py::make_tuple("kind", "u1"));
  fields.append(py::make_tuple("depth", "<u2"));
  fields.append(py::make_tuple("path", "<u4"));
  py::object array = np.attr("zeros")(vpls.size(), np.attr("dtype")(fields));
  array["position"] = vec3_column(vpls, &Vpl::position);
  array["normal"] = vec3_column(vpls, &Vpl::normal);
  array["intensity"] = vec3_column(vpls, &Vpl::intensity);
  array["kind"] = column<std::uint8_t>(vpls, [](const Vpl& v) { return v.kind; });
  array["depth"] = column<std::uint16_t>(vpls, [](const Vpl& v) { return v.depth; });
  array["path"] = column<std::uint32_t>(vpls, [](const Vpl& v) { return v.path; });
  return array;
}

} // namespace

py::tuple walk(const Scene& scene, std::uint32_t paths, const std::string& sequence,
               std::uint64_t seed) {
  require_at_least_one(paths, "paths");
  WalkOptions options;
  options.paths = paths;
  options.sequence = parse_sequence(sequence);
  options.seed = seed;
  VplSet set;
  {
    py::gil_scoped_release released;
    Log log;
    const RayScene rays(scene);
    set = quasi_random_walk(scene, rays, options, log);
  }
  py::dict stats;
  stats["paths"] = set.paths;
  stats["rho_bar"] = set.rho_bar;
  stats["l_max"] = set.l_max;
  stats["planned"] = set.planned;
  stats["depth_capped"] = set.depth_capped;
  return py::make_tuple(vpl_array(set.vpls), stats);
}

} // namespace irad::python
