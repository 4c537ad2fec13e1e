#pragma once
// irad bench --load FILE: what loading a large scene costs. Each of `runs` runs loads FILE
// (load_gltf: read, JSON, validation, decoding, the triangle soup), builds the Embree BVH
// (RayScene) and uploads the scene to GL (the RasterRenderer's construction: context, shaders
// and the GpuScene buffers; gl_context is the same construction for a one-quad scene, so
// gl_upload - gl_context is the scene's buffers); the times are medians over the runs. The
// stages keep what the earlier ones built, as `irad render` does: the BVH stage's memory
// includes the scene, the upload's the scene and the BVH. Memory is the resident set
// (/proc/self/status): VmRSS before the run, and VmHWM, the kernel's high-water mark, reset
// before each stage by writing 5 to /proc/self/clear_refs, so each stage's peak is its own (when
// the reset is refused, the peak is the process's since its start and says so). glibc's mmap
// threshold is fixed at 128 KiB for the bench, so freed large blocks leave the resident set.
#include "core/util/log.h"

#include <cstddef>
#include <string>
#include <vector>

namespace irad::apps {

struct LoadBenchOptions {
  std::string file;
  std::string out_dir = "out/bench";
  int runs = 3;
  bool raster = true;       // the GL upload stage (off: load and BVH only)
  std::string memory_trace; // CSV of VmRSS sampled every millisecond during the first run
};

struct LoadStage {
  std::string name; // load, bvh, gl_context, gl_upload
  std::vector<double> seconds;
  std::vector<std::size_t> peak_bytes;  // VmHWM during the stage (since the reset)
  std::vector<std::size_t> after_bytes; // VmRSS when it finished
};

struct LoadBenchResult {
  std::string file;
  std::size_t file_bytes = 0, triangles = 0, vertices = 0;
  std::size_t decoded_bytes = 0; // positions + normals + uvs (+ uvs1, colors) + triangles +
                                 // triangle_material of the loaded Scene
  std::vector<std::size_t> baseline_bytes; // VmRSS before each run
  bool peak_reset = true;                  // clear_refs worked: per-stage peaks
  std::vector<LoadStage> stages;
};

LoadBenchResult run_load_bench(const LoadBenchOptions& options, Log& log);
// OUT/load.csv: one row per stage, medians (and min, max) over the runs.
void write_load_csv(const LoadBenchResult& result, const std::string& path);
std::string load_table(const LoadBenchResult& result);

} // namespace irad::apps
