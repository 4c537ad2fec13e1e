#include "apps/bench/load_bench.h"
#include "apps/bench/stopwatch.h"

#include "core/gltf/loader.h"
#include "core/scene/scene_builder.h"
#include "core/util/error.h"
#include "raster/raster_renderer.h"
#include "walk/rays/ray_scene.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <malloc.h>
#include <optional>
#include <thread>

namespace irad::apps {

namespace {

// A field of /proc/self/status in bytes ("VmRSS", "VmHWM"); 0 when unreadable.
std::size_t status_bytes(const char* field) {
  std::ifstream in("/proc/self/status");
  std::string line;
  const std::string key = std::string(field) + ":";
  while (std::getline(in, line))
    if (line.rfind(key, 0) == 0) return std::stoull(line.substr(key.size())) * 1024;
  return 0;
}

// Resets VmHWM to the current VmRSS (Linux >= 4.0); false when refused.
bool reset_peak() {
  std::ofstream out("/proc/self/clear_refs");
  out << "5";
  out.flush();
  return static_cast<bool>(out);
}

std::size_t decoded_bytes(const Scene& s) {
  return s.positions.size() * sizeof(glm::vec3) + s.normals.size() * sizeof(glm::vec3) +
         s.uvs.size() * sizeof(glm::vec2) + s.uvs1.size() * sizeof(glm::vec2) +
         s.colors.size() * sizeof(glm::vec4) + s.triangles.size() * sizeof(glm::uvec3) +
         s.triangle_material.size() * sizeof(std::uint32_t);
}

// VmRSS every millisecond, in a thread, while it lives.
class RssSampler {
public:
  RssSampler() : start_(Clock::now()), thread_([this] { loop(); }) {}
  ~RssSampler() { stop(); }
  void stop() {
    done_ = true;
    if (thread_.joinable()) thread_.join();
  }
  void mark(const std::string& what) { marks_.push_back({since(start_), what}); }
  void write(const std::string& path) {
    stop();
    std::ofstream out(path);
    out << "seconds,rss_bytes,event\n";
    std::size_t m = 0;
    for (const auto& [t, rss] : samples_) {
      for (; m < marks_.size() && marks_[m].first <= t; ++m)
        out << fmt::format("{:.4f},,{}\n", marks_[m].first, marks_[m].second);
      out << fmt::format("{:.4f},{},\n", t, rss);
    }
    if (!out) throw Error(path, "", "cannot write");
  }

private:
  void loop() {
    while (!done_) {
      samples_.push_back({since(start_), status_bytes("VmRSS")});
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  }
  Clock::time_point start_;
  std::atomic<bool> done_{false};
  std::vector<std::pair<double, std::size_t>> samples_;
  std::vector<std::pair<double, std::string>> marks_; // written by the bench's thread only
  std::thread thread_;
};

template <class T>
T median(std::vector<T> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? T{} : v[v.size() / 2];
}

// The smallest scene the raster renderer takes: its construction is the context and the
// shaders, so gl_upload - gl_context is what the large scene's buffers cost.
Scene tiny_scene() {
  Scene s;
  const std::uint32_t m = add_material(s, glm::vec3(0.5f), glm::vec3(1.0f));
  add_quad(s, {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, m);
  s.cameras.push_back(look_at({0.5f, 0.5f, 2.0f}, {0.5f, 0.5f, 0.0f}, {0, 1, 0}, 0.8f));
  finish(s);
  return s;
}

double mib(std::size_t bytes) {
  return static_cast<double>(bytes) / (1024.0 * 1024.0);
}

} // namespace

LoadBenchResult run_load_bench(const LoadBenchOptions& o, Log& log) {
  if (o.runs < 1) throw Error("", "--runs", "must be at least 1");
  if (!std::filesystem::is_regular_file(o.file)) throw Error(o.file, "", "no such file");
  // A fixed threshold (no dynamic growth after frees): blocks of 128 KiB and more are mmap'ed and
  // go back to the system when freed, so a run starts where the previous one did (irad's main
  // maps no block apart: M_MMAP_MAX back to glibc's default).
  mallopt(M_MMAP_MAX, 65536);
  mallopt(M_MMAP_THRESHOLD, 128 * 1024);
  std::filesystem::create_directories(o.out_dir);
  if (!o.memory_trace.empty() && std::filesystem::path(o.memory_trace).has_parent_path())
    std::filesystem::create_directories(std::filesystem::path(o.memory_trace).parent_path());
  LoadBenchResult r;
  r.file = o.file;
  r.file_bytes = std::filesystem::file_size(o.file);
  for (const char* name : {"load", "bvh", "gl_context", "gl_upload"}) {
    if (!o.raster && name[0] == 'g') continue;
    r.stages.emplace_back().name = name;
  }
  Log quiet([](const std::string&) {});
  LoadLimits limits;
  limits.max_triangles = std::uint64_t(1) << 26;
  for (int run = 0; run < o.runs; ++run) {
    malloc_trim(0);
    std::optional<RssSampler> sampler;
    if (run == 0 && !o.memory_trace.empty()) sampler.emplace();
    r.baseline_bytes.push_back(status_bytes("VmRSS"));
    std::size_t stage = 0;
    auto measure = [&](const char* name, auto&& body) {
      if (sampler) sampler->mark(std::string("start ") + name);
      r.peak_reset = reset_peak() && r.peak_reset;
      const auto t0 = Clock::now();
      body();
      LoadStage& s = r.stages.at(stage++);
      s.seconds.push_back(since(t0));
      s.peak_bytes.push_back(status_bytes("VmHWM"));
      s.after_bytes.push_back(status_bytes("VmRSS"));
      if (sampler) sampler->mark(std::string("end ") + name);
    };
    {
      Scene scene;
      measure("load", [&] { scene = load_gltf(o.file, run == 0 ? log : quiet, limits); });
      r.triangles = scene.triangle_count();
      r.vertices = scene.positions.size();
      r.decoded_bytes = decoded_bytes(scene);
      std::optional<RayScene> rays;
      measure("bvh", [&] { rays.emplace(scene); });
      if (o.raster) {
        const Scene tiny = tiny_scene();
        std::optional<RasterRenderer> raster;
        measure("gl_context", [&] { raster.emplace(tiny, RasterOptions{}); });
        raster.reset();
        measure("gl_upload", [&] { raster.emplace(scene, RasterOptions{}); });
      }
    }
    if (sampler) sampler->write(o.memory_trace);
    log.info(fmt::format("bench: load run {}/{}: {}", run + 1, o.runs,
                         fmt::join(
                             [&] {
                               std::vector<std::string> parts;
                               for (const LoadStage& s : r.stages)
                                 parts.push_back(
                                     fmt::format("{} {:.3f} s", s.name, s.seconds.back()));
                               return parts;
                             }(),
                             ", ")));
  }
  write_load_csv(r, o.out_dir + "/load.csv");
  return r;
}

void write_load_csv(const LoadBenchResult& r, const std::string& path) {
  std::ofstream out(path);
  out << "file,file_bytes,triangles,vertices,decoded_bytes,runs,stage,seconds_median,seconds_min,"
         "seconds_max,baseline_rss_bytes,peak_rss_bytes,rss_after_bytes,peak_over_decoded,"
         "peak_reset\n";
  const std::size_t base = median(r.baseline_bytes);
  for (const LoadStage& s : r.stages) {
    const std::size_t peak = median(s.peak_bytes);
    out << fmt::format("{},{},{},{},{},{},{},{:.6f},{:.6f},{:.6f},{},{},{},{:.3f},{}\n",
                       std::filesystem::path(r.file).filename().string(), r.file_bytes, r.triangles,
                       r.vertices, r.decoded_bytes, s.seconds.size(), s.name, median(s.seconds),
                       *std::min_element(s.seconds.begin(), s.seconds.end()),
                       *std::max_element(s.seconds.begin(), s.seconds.end()), base, peak,
                       median(s.after_bytes),
                       static_cast<double>(peak - std::min(peak, base)) /
                           static_cast<double>(std::max<std::size_t>(r.decoded_bytes, 1)),
                       r.peak_reset ? 1 : 0);
  }
  if (!out) throw Error(path, "", "cannot write");
}

std::string load_table(const LoadBenchResult& r) {
  const std::size_t base = median(r.baseline_bytes);
  std::string t = fmt::format(
      "{}: {:.1f} MiB, {} triangles, {} vertices; decoded geometry {:.1f} MiB; resident before "
      "load {:.1f} MiB; medians of {} runs\n",
      r.file, mib(r.file_bytes), r.triangles, r.vertices, mib(r.decoded_bytes), mib(base),
      r.stages.empty() ? 0 : r.stages[0].seconds.size());
  t += fmt::format("{:<11} {:>9} {:>15} {:>14} {:>16}\n", "stage", "seconds",
                   r.peak_reset ? "stage peak MiB" : "peak* MiB", "after MiB", "(peak-before)/geo");
  std::size_t overall = 0;
  for (const LoadStage& s : r.stages) {
    const std::size_t peak = median(s.peak_bytes);
    overall = std::max(overall, peak);
    t += fmt::format("{:<11} {:>9.3f} {:>15.1f} {:>14.1f} {:>16.2f}\n", s.name, median(s.seconds),
                     mib(peak), mib(median(s.after_bytes)),
                     static_cast<double>(peak - std::min(peak, base)) /
                         static_cast<double>(std::max<std::size_t>(r.decoded_bytes, 1)));
  }
  t += fmt::format("peak resident {:.1f} MiB = before {:.1f} + {:.1f} MiB = {:.2f} x the decoded "
                   "geometry{}\n",
                   mib(overall), mib(base), mib(overall - std::min(overall, base)),
                   static_cast<double>(overall - std::min(overall, base)) /
                       static_cast<double>(std::max<std::size_t>(r.decoded_bytes, 1)),
                   r.peak_reset ? "" : " (* VmHWM could not be reset: peaks since start)");
  return t;
}

} // namespace irad::apps
