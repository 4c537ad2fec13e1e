// irad: instant radiosity from the command line. Each subcommand lives in its own file; errors
// from anywhere arrive here as exceptions, are printed on one line, and exit with code 1.
#include "apps/commands.h"
#include "core/util/error.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#if defined(__GLIBC__)
#include <malloc.h>
#include <unistd.h>
#endif

namespace {

// llvmpipe allocates and frees its vertex and bin buffers per draw; with glibc's defaults the
// freed top of the heap goes back to the kernel each time and comes back as fresh zeroed pages:
// a fifth of a zdm2 render (256x256, N = 64) is page faults. Keeping up to 128 MiB of freed
// heap renders it in 3.1-3.7 s against 4.4-5.0 s (docs/performance.md).
// No block is mapped apart, however big: a big scene's arrays (the loader's, the shadow
// hierarchy's build, the GL upload's copies) come from the heap and reuse what the one before
// freed, where mapped apart each came as fresh pages, which cost this machine about 2.7 ms per
// MiB (a 120 MiB array: 320 ms mapped, 2.5 ms reused). The stages that leave big holes hand
// them back when done (core/util/freed_memory.h: after the load, the hierarchy's tree, a build
// that runs first, the BVH, the raster's taking of its hierarchies). A cold render of the
// 10M-triangle sphere box: 162k page faults against 308k mapped apart, 12.4-15.0 s
// against 14.7-17.2 s (docs/performance.md "Freed heap is kept"). One arena for all threads: the
// shadow hierarchy's build allocates on its own threads, and the holes it leaves in their arenas
// stayed resident after malloc_trim (the 10M sphere box's cold peak 1125-1151 MiB against 1039 with
// one arena, the 10M terrain's 1208 against 1087, the 2.1M sphere box's 525-528 against 467-471;
// one run each, in turn). No render measured slower: the 2.1M sphere box warm 1.70-2.21 s
// against 1.74-2.15 (four pairs), cold 3.45-3.68 against 3.56-3.91, zdm2 7.18-7.33
// against 7.21-8.11 (two pairs).
void keep_freed_heap() {
#if defined(__GLIBC__)
  mallopt(M_TRIM_THRESHOLD, 128 << 20);
  mallopt(M_TOP_PAD, 16 << 20);
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_ARENA_MAX, 1);
#endif
}

// The heap in transparent huge pages (glibc's tunable glibc.malloc.hugetlb=1: each extension of
// the heap advised MADV_HUGEPAGE, which the kernel's usual "madvise" mode asks for): a big
// scene's arrays then cost a page fault per 2 MiB instead of per 4 KiB, where each fault is dear
// on this machine: a cold render of the 10M sphere box at 256x256 faults 15k times against 175k
// without, and takes 0.3-1.5 s less in most pairs (docs/performance.md "Huge pages"). glibc reads
// its tunables only when a process starts, so the program runs itself once more with the tunable
// added to GLIBC_TUNABLES; not where the caller's GLIBC_TUNABLES names hugetlb already (=0 turns it
// off), and where /proc/self/exe cannot be run it goes on as it started.
void exec_with_huge_heap(char** argv) {
#if defined(__GLIBC__) && defined(__linux__)
  constexpr const char* kMarker = "IRAD_HUGE_HEAP"; // set: this is the run with the tunable
  if (std::getenv(kMarker)) return;
  const char* given = std::getenv("GLIBC_TUNABLES");
  const std::string tunables = given ? given : "";
  if (tunables.find("glibc.malloc.hugetlb") != std::string::npos) return;
  setenv(kMarker, "1", 1);
  setenv("GLIBC_TUNABLES",
         ((tunables.empty() ? "" : tunables + ":") + "glibc.malloc.hugetlb=1").c_str(), 1);
  execv("/proc/self/exe", argv); // returns only where it failed
  if (given) {
    setenv("GLIBC_TUNABLES", given, 1);
  } else {
    unsetenv("GLIBC_TUNABLES");
  }
  unsetenv(kMarker);
#else
  (void)argv;
#endif
}

} // namespace

int main(int argc, char** argv) {
  exec_with_huge_heap(argv);
  keep_freed_heap();
  CLI::App app{"irad: diffuse global illumination with Keller's Instant Radiosity"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "irad 0.1");
  irad::apps::Commands commands;
  irad::apps::add_render_command(app, commands);
  irad::apps::add_compare_command(app, commands);
  irad::apps::add_scene_command(app, commands);
  irad::apps::add_bench_command(app, commands);
  irad::apps::add_convert_command(app, commands);
  irad::apps::add_walkthrough_command(app, commands);
  irad::apps::add_merge_command(app, commands);
  try {
    app.parse(argc, argv);
    return commands.run();
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "irad: error: %s (see irad --help)\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "irad: error: %s\n", e.what());
    return 1;
  }
}
