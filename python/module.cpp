// The Python module `irad` (pybind11): irad.load -> Scene, irad.render -> (image, stats),
// irad.walk -> (VPLs, stats), irad.walkthrough -> frames, irad.compare, irad.read_exr,
// irad.write_exr, irad.Error. A thin layer over the library (lib/irad/irad.h): every error is
// irad::Error, raised as irad.Error with the CLI's one line as its text.
#include "arrays.h"
#include "core/animation/animation.h"
#include "core/environment/environment_file.h"
#include "core/lights/light_sampler.h"
#include "irad/irad.h"
#include "render_call.h"
#include "walkthrough_frames.h"

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <optional>

namespace py = pybind11;
using namespace pybind11::literals;

namespace irad::python {

namespace {

struct LoadKeywords {
  std::string scene; // the glTF scene by name or index
  std::optional<std::uint64_t> max_triangles, max_file_size_mib;
  std::optional<int> max_texture_size;
  std::optional<float> time;
  std::string env, env_color, sky;
  float env_strength = 1.0f, env_rotate = 0.0f;
  bool env_visible = true, quiet = false;
};

std::shared_ptr<Scene> load(const std::string& path, const LoadKeywords& k) {
  SceneOptions o;
  o.gltf_scene = k.scene;
  if (k.max_triangles) o.limits.max_triangles = *k.max_triangles;
  if (k.max_file_size_mib) o.limits.max_file_bytes = *k.max_file_size_mib << 20;
  if (k.max_texture_size) o.limits.max_texture_size = *k.max_texture_size;
  o.lighting.env = k.env;
  if (!k.env_color.empty()) o.lighting.env_color = parse_env_color(k.env_color, "env_color");
  o.lighting.sky = k.sky;
  o.lighting.strength = k.env_strength;
  o.lighting.rotate_degrees = k.env_rotate;
  o.lighting.visible = k.env_visible;
  o.time = k.time;
  py::gil_scoped_release released;
  Log log;
  log.set_quiet(k.quiet);
  return std::make_shared<Scene>(load_scene(path, o, log));
}

py::dict lights(const Scene& scene) {
  const LightSummary s = summarize_lights(scene);
  return py::dict("emissive_triangles"_a = s.emissive_triangles,
                  "emissive_materials"_a = s.emissive_materials, "point"_a = s.point,
                  "spot"_a = s.spot, "directional"_a = s.directional, "suns"_a = s.suns,
                  "environment"_a = s.environment.empty() ? py::object(py::none())
                                                          : py::object(py::str(s.environment)));
}

py::tuple vec3(const glm::vec3& v) {
  return py::make_tuple(v.x, v.y, v.z);
}

void bind_scene(py::module_& m) {
  py::class_<Scene, std::shared_ptr<Scene>>(m, "Scene", "A loaded glTF scene (irad.load)")
      .def_property_readonly("source", [](const Scene& s) { return s.source; })
      .def_property_readonly("triangles", &Scene::triangle_count)
      .def_property_readonly(
          "bounds",
          [](const Scene& s) { return py::make_tuple(vec3(s.bounds.lo), vec3(s.bounds.hi)); })
      .def_property_readonly("cameras",
                             [](const Scene& s) {
                               py::list names;
                               for (const Camera& c : s.cameras) names.append(c.name);
                               return names;
                             })
      .def_property_readonly("lights", &lights)
      .def_property_readonly(
          "light_power", [](const Scene& s) { return LightSampler(s).total_power(); },
          "radiant power of every light (the walk's Phi: depth-0 VPLs carry Phi/N each)")
      .def_property_readonly(
          "rho_bar", [](const Scene& s) { return mean_albedo(s); },
          "the mean albedo the walk's particle counts n_j = floor(rho_bar^j N) use")
      .def_property_readonly(
          "duration", [](const Scene& s) { return s.animation ? s.animation->end() : 0.0f; },
          "seconds of the glTF animation (its last key); 0 without one")
      .def("__repr__", [](const Scene& s) {
        return "<irad.Scene " + s.source + ": " + std::to_string(s.triangle_count()) +
               " triangles>";
      });
}

py::dict metrics(const ImageMetrics& m) {
  const auto rgb = [](const std::array<double, 3>& v) { return py::make_tuple(v[0], v[1], v[2]); };
  return py::dict("block"_a = m.block, "rmse"_a = m.rmse, "rmse_rgb"_a = rgb(m.rmse_rgb),
                  "relmse"_a = m.relmse, "mean_ratio"_a = rgb(m.mean_ratio),
                  "max_abs_error"_a = m.max_abs_error,
                  "nonfinite"_a = py::make_tuple(m.nonfinite_a, m.nonfinite_b),
                  "pixels"_a = m.pixels, "samples"_a = m.samples);
}

void bind_functions(py::module_& m) {
  m.def(
      "load",
      [](const std::string& path, const std::string& scene,
         std::optional<std::uint64_t> max_triangles, std::optional<std::uint64_t> max_file_size,
         std::optional<int> max_texture_size, std::optional<float> time, const std::string& env,
         const std::string& env_color, const std::string& sky, float env_strength, float env_rotate,
         bool env_visible, bool quiet) {
        return load(path, {scene, max_triangles, max_file_size, max_texture_size, time, env,
                           env_color, sky, env_strength, env_rotate, env_visible, quiet});
      },
      "path"_a, py::kw_only(), "scene"_a = "", "max_triangles"_a = py::none(),
      "max_file_size"_a = py::none(), "max_texture_size"_a = py::none(), "time"_a = py::none(),
      "env"_a = "", "env_color"_a = "", "sky"_a = "", "env_strength"_a = 1.0f,
      "env_rotate"_a = 0.0f, "env_visible"_a = true, "quiet"_a = false,
      "Loads a glTF scene (limits: max_triangles, max_file_size in MiB, max_texture_size; "
      "lighting: env, env_color 'R,G,B', sky 'ELEV[,AZIM[,TURB]]', ...; time: the animation's "
      "pose)");
  m.def(
      "render",
      [](const Scene& scene, std::optional<std::pair<int, int>> size,
         std::optional<std::uint32_t> paths, const std::string& estimator, std::uint32_t spp,
         std::uint64_t seed, float clamp, std::optional<int> interleave, int batch, int shadow_res,
         const std::string& sequence, bool jitter, const std::string& camera,
         std::optional<float> time, unsigned threads, bool bias_compensation, const std::string& gl,
         std::optional<std::size_t> clusters, std::uint32_t rounds,
         const std::string& interleave_edges, float traced_roughness, std::uint32_t glossy_samples,
         const std::string& visibility) {
        return render(scene, {size,
                              paths,
                              estimator,
                              spp,
                              seed,
                              clamp,
                              interleave,
                              batch,
                              shadow_res,
                              sequence,
                              jitter,
                              camera,
                              time,
                              threads,
                              bias_compensation,
                              gl,
                              clusters,
                              rounds,
                              interleave_edges,
                              traced_roughness,
                              glossy_samples,
                              visibility});
      },
      "scene"_a, py::kw_only(), "size"_a = py::none(), "paths"_a = py::none(),
      "estimator"_a = "raster", "spp"_a = 64u, "seed"_a = 0u, "clamp"_a = 0.05f,
      "interleave"_a = py::none(), "batch"_a = 64, "shadow_res"_a = 0, "sequence"_a = "halton",
      "jitter"_a = false, "camera"_a = "", "time"_a = py::none(), "threads"_a = 0u,
      "bias_compensation"_a = false, "gl"_a = "auto", "clusters"_a = py::none(), "rounds"_a = 1u,
      "interleave_edges"_a = "auto", "traced_roughness"_a = RenderOptions{}.traced_roughness,
      "glossy_samples"_a = RenderOptions{}.glossy_samples, "visibility"_a = "auto",
      "Renders the scene: (float32 array (h, w, 3), stats dict); paths, clusters and interleave "
      "None: the light budget, as irad render's auto; rounds: the mean of independent light "
      "sets; interleave_edges: auto, traced, shaded or off, as irad render's --interleave-edges; "
      "traced_roughness, glossy_samples, visibility: irad render's --traced-roughness, "
      "--glossy-samples, --visibility; "
      "the GIL is released, Ctrl-C cancels (KeyboardInterrupt)");
  m.def("walk", &walk, "scene"_a, py::kw_only(), "paths"_a = 256u, "sequence"_a = "halton",
        "seed"_a = 0u, "The quasi-random walk's VPLs: (structured array, stats dict)");
  m.def(
      "compare",
      [](const py::array& image, const py::array& reference, int block) {
        const Image a = to_image(image, "image");
        const Image b = to_image(reference, "reference");
        require_same_size(a, "image", b, "reference");
        return metrics(compare_images(a, b, block));
      },
      "image"_a, "reference"_a, py::kw_only(), "block"_a = 1,
      "The metrics of `irad compare` (rmse, relmse, mean_ratio, ...) of image against "
      "reference");
  m.def(
      "read_exr", [](const std::string& path) { return to_array(read_exr(path), 4); }, "path"_a,
      "An EXR file as a float32 array (h, w, 4), RGBA");
  m.def(
      "write_exr",
      [](const std::string& path, const py::array& image) {
        write_exr(path, to_image(image, "image"));
      },
      "path"_a, "image"_a, "Writes a float32 (h, w, 3) or (h, w, 4) array as an EXR file");
}

void bind_walkthrough(py::module_& m) {
  py::class_<WalkthroughFrames>(m, "Walkthrough", "Frames of irad.walkthrough, an iterator")
      .def("__iter__", [](WalkthroughFrames& w) -> WalkthroughFrames& { return w; })
      .def("__next__", &WalkthroughFrames::next)
      .def_property_readonly("mode", &WalkthroughFrames::mode)
      .def_property_readonly("paths", &WalkthroughFrames::paths);
  m.def(
      "walkthrough",
      [](const Scene& scene, std::pair<int, int> frames, const std::string& mode,
         std::uint32_t paths, std::pair<int, int> size, float fps, float orbit,
         const std::string& camera, const std::string& gl, bool warm_up) {
        return std::make_unique<WalkthroughFrames>(
            scene, WalkthroughKeywords{frames, mode, paths, size, fps, orbit, camera, gl, warm_up});
      },
      "scene"_a, py::kw_only(), "frames"_a = std::pair<int, int>{0, 60}, "mode"_a = "auto",
      "paths"_a = 64u, "size"_a = std::pair<int, int>{256, 256}, "fps"_a = 30.0f, "orbit"_a = 0.0f,
      "camera"_a = "", "gl"_a = "auto", "warm_up"_a = true,
      "The real-time frames of `irad walkthrough` (frames (A, B), B exclusive): an iterator of "
      "float32 arrays (h, w, 3)");
}

} // namespace

} // namespace irad::python

PYBIND11_MODULE(irad, m) {
  m.doc() = "irad: diffuse global illumination with Keller's Instant Radiosity";
  py::register_exception<irad::Error>(m, "Error", PyExc_RuntimeError);
  irad::python::bind_scene(m);
  irad::python::bind_functions(m);
  irad::python::bind_walkthrough(m);
}
