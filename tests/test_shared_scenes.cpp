// The third-party glTF files of ../shared/scenes (none carries a light) render without options:
// the command line lights each with the uniform white environment and says so in exactly one
// warning. Raster, the default estimator, small and with few paths: what is checked
// is that the file is accepted and lit, not the image's accuracy (the furnace and the
// environment tests do that).
#include "core/image/image_io.h"
#include "tests/test_paths.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <utility>
#include <vector>

namespace fs = std::filesystem;

namespace IRAD_UNITY_ID {

const fs::path kScenes = fs::path(IRAD_SOURCE_DIR) / "../shared/scenes";

std::vector<fs::path> shared_scene_files() {
  std::vector<fs::path> files;
  if (!fs::is_directory(kScenes)) return files;
  for (const fs::directory_entry& folder : fs::directory_iterator(kScenes)) {
    if (!folder.is_directory()) continue;
    for (const fs::directory_entry& f : fs::directory_iterator(folder.path()))
      if (f.path().extension() == ".gltf" || f.path().extension() == ".glb")
        files.push_back(f.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::size_t count(const std::string& text, const std::string& needle) {
  std::size_t n = 0;
  for (std::size_t at = 0; (at = text.find(needle, at)) != std::string::npos; ++at) ++n;
  return n;
}

TEST(SharedScenes, UnlitFilesRenderWithTheWhiteEnvironmentAndOneWarning) {
  const std::vector<fs::path> files = shared_scene_files();
  if (files.empty()) GTEST_SKIP() << "no " << kScenes;
  const fs::path dir = fs::path(::testing::TempDir()) / "irad_shared_scenes";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const auto render = [&](const fs::path& file, const std::string& options) {
    const fs::path out = dir / (file.stem().string() + ".exr"), err = dir / "stderr.txt";
    const std::string cmd = std::string(IRAD_BINARY) + " render '" + file.string() + "' -o '" +
                            out.string() + "' --size 48x48 --paths 16 " + options +
                            " > /dev/null 2> '" + err.string() + "'";
    const int status = std::system(cmd.c_str());
    return std::pair{WEXITSTATUS(status), read_text(err)};
  };
  for (const fs::path& file : files) {
    SCOPED_TRACE(file.string());
    const auto [code, text] = render(file, "");
    ASSERT_EQ(code, 0) << text;
    EXPECT_EQ(count(text, "uniform white environment of radiance 1"), 1u) << text;
    EXPECT_EQ(count(text, file.string() + ": the scene has no light of its own"), 1u) << text;
    // Lit: with the background black, the surfaces the camera sees carry light.
    const auto [dark_code, dark_text] = render(file, "--env-visible off");
    ASSERT_EQ(dark_code, 0) << dark_text;
    const irad::Image image = irad::read_exr(dir / (file.stem().string() + ".exr"));
    float brightest = 0.0f;
    for (const glm::vec4& p : image.pixels()) brightest = std::max(brightest, p.g);
    EXPECT_GT(brightest, 0.1f);
  }
  fs::remove_all(dir);
}

} // namespace
