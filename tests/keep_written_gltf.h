#pragma once
// For ctest's gltf_validator (tests/validate_written_gltf.sh): when the environment variable
// IRAD_GLTF_OUT names a folder, a test that wrote a glTF file through irad::write_gltf keeps a
// copy there as NAME, for the Khronos validator to check. Without the variable it does nothing.
#include <cstdlib>
#include <filesystem>
#include <string>

namespace irad::test {

inline void keep_written_gltf(const std::filesystem::path& written, const std::string& name) {
  const char* out = std::getenv("IRAD_GLTF_OUT");
  if (out == nullptr || *out == '\0') return;
  std::filesystem::copy_file(written, std::filesystem::path(out) / name,
                             std::filesystem::copy_options::overwrite_existing);
}

} // namespace irad::test
