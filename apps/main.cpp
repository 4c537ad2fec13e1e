// irad: instant radiosity from the command line. Each subcommand lives in its own file; errors
// from anywhere arrive here as exceptions, are printed on one line, and exit with code 1.
#include "apps/commands.h"
#include "core/util/error.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <unistd.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace {

// llvmpipe allocates and frees its vertex and bin buffers per draw; with glibc's defaults the
// freed top of the heap goes back to the kernel each time and comes back as fresh zeroed pages:
// a fifth of a zdm2 render (256x256, N = 64) is page faults. Keeping up to 128 MiB of freed
// heap renders it in 3.1-3.7 s against 4.4-5.0 s (docs/performance.md). Blocks from 32 MiB up (a
// big scene's arrays) are mapped apart and go back whole when freed: kept in the heap instead
// they were no faster under huge pages (below) and left their holes resident (the 10M terrain's
// rt-vpl peak 1.87 GiB against 1.57 GiB).
void keep_freed_heap() {
#if defined(__GLIBC__)
  mallopt(M_TRIM_THRESHOLD, 128 << 20);
  mallopt(M_TOP_PAD, 16 << 20);
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
#endif
}

// glibc backs its heap with transparent huge pages (madvise) only under its tunable
// glibc.malloc.hugetlb=1, which it reads when a process starts: so irad starts itself once more
// with it, unless GLIBC_TUNABLES is set already (that choice stands; set it empty to opt out).
// With 2 MiB pages (glibc advises them for its heap and its mapped blocks) a big scene's arrays,
// Embree's and llvmpipe's buffers take a 512th of the page faults: the 2.1M sphere box (256x256,
// default options) renders in 6.81 s against 9.06 s with an empty hierarchy cache, 3.84 s against
// 5.22 s with it, rt-vpl in 5.34 s against 6.42 s (medians of three, GLIBC_TUNABLES empty for
// the second; docs/performance.md "Huge pages"). If the exec fails, irad goes on as it is.
void restart_with_huge_pages(char** argv) {
#if defined(__GLIBC__) && defined(__linux__)
  if (std::getenv("GLIBC_TUNABLES") != nullptr) return;
  if (setenv("GLIBC_TUNABLES", "glibc.malloc.hugetlb=1", 1) != 0) return;
  execv("/proc/self/exe", argv);
  unsetenv("GLIBC_TUNABLES");
#endif
}

} // namespace

int main(int argc, char** argv) {
  restart_with_huge_pages(argv);
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
