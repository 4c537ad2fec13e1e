// libFuzzer target: scene loading and validation (irad::load_gltf) on a .gltf or .glb file
// written from the input. Build with `cmake --preset fuzz && cmake --build --preset fuzz`, run
// with fuzz/run.sh. An input may only load or throw irad::Error.
#include "fuzz/fuzz_input.h"

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <unistd.h>

namespace {

std::filesystem::path g_dir;

} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  // One folder per process (libFuzzer's -jobs/-workers run several), on tmpfs when there is one.
  const std::filesystem::path base = std::filesystem::is_directory("/dev/shm")
                                         ? "/dev/shm"
                                         : std::filesystem::temp_directory_path();
  g_dir = base / ("irad_fuzz_" + std::to_string(::getpid()));
  irad::fuzz::prepare_dir(g_dir);
  std::atexit([] {
    std::error_code ec;
    std::filesystem::remove_all(g_dir, ec);
  });
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  irad::fuzz::load_input(g_dir, data, size);
  return 0;
}
