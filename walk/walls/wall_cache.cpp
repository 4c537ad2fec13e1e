#include "walk/walls/wall_cache.h"

#include "walk/walls/thin_walls.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <embree3/rtcore_config.h>
#include <fstream>
#include <xxhash.h>

namespace irad {

namespace fs = std::filesystem;

namespace {

constexpr char kMagic[8] = {'I', 'R', 'A', 'D', 'W', 'A', 'L', 'L'};
// The file's version: raise it whenever the layout or the scan's results change.
constexpr std::uint32_t kFormat = 1;

// The whole file: what the scan found, then the checksum of the bytes before it.
struct WallFile {
  char magic[8];
  std::uint32_t format, embree;
  std::uint64_t key_low, key_high;
  float searched; // the reach scanned, a fraction of the diagonal
  float gap;      // the least gap found within it, a fraction of the diagonal (<= searched)
  std::uint64_t checksum;
};
static_assert(sizeof(WallFile) == 48, "the file has no padding");

std::uint64_t checksum_of(const WallFile& f) {
  return XXH3_64bits(&f, offsetof(WallFile, checksum));
}

// What the scan reads: the geometry, the diagonal, the ray epsilon, the format and Embree.
ClusterKey wall_key(const Scene& scene, const RayScene& rays) {
  KeyHasher hasher;
  const std::uint32_t versions[2] = {kFormat, RTC_VERSION};
  hasher.add(versions, sizeof versions);
  const float scales[2] = {scene.bounds.diagonal(), rays.epsilon()};
  hasher.add(scales, sizeof scales);
  const std::uint64_t counts[2] = {scene.positions.size(), scene.triangles.size()};
  hasher.add(counts, sizeof counts);
  hasher.add(scene.positions.data(), scene.positions.size() * sizeof(glm::vec3));
  hasher.add(scene.triangles.data(), scene.triangles.size() * sizeof(glm::uvec3));
  return hasher.key();
}

// The file's (searched, gap) for `key`, or why it is not usable.
bool read_wall(const fs::path& path, const ClusterKey& key, WallFile& f, std::string& why) {
  std::ifstream in(path, std::ios::binary);
  in.read(reinterpret_cast<char*>(&f), sizeof f);
  if (!in || in.peek() != std::ifstream::traits_type::eof()) {
    why = "not the size of a wall file";
    return false;
  }
  if (std::memcmp(f.magic, kMagic, sizeof kMagic) != 0 || f.format != kFormat ||
      f.embree != RTC_VERSION) {
    why = "another format or Embree version";
    return false;
  }
  if (checksum_of(f) != f.checksum) {
    why = "checksum mismatch";
    return false;
  }
  if (f.key_low != key.low || f.key_high != key.high) {
    why = "the key of another scene";
    return false;
  }
  if (!std::isfinite(f.searched) || !std::isfinite(f.gap) || f.gap < 0.0f || f.gap > f.searched) {
    why = "a gap outside its reach";
    return false;
  }
  return true;
}

bool write_wall(const fs::path& path, const ClusterKey& key, float searched, float gap) {
  WallFile f{};
  std::memcpy(f.magic, kMagic, sizeof kMagic);
  f.format = kFormat;
  f.embree = RTC_VERSION;
  f.key_low = key.low;
  f.key_high = key.high;
  f.searched = searched;
  f.gap = gap;
  f.checksum = checksum_of(f);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(&f), sizeof f);
  out.close();
  return static_cast<bool>(out);
}

} // namespace

float cached_thinnest_wall(const Scene& scene, const RayScene& rays, float up_to,
                           const fs::path& folder, CacheResult* result,
                           const std::function<float()>& scan) {
  const auto answer = [&] { return scan ? scan() : thinnest_wall(scene, rays, up_to); };
  CacheResult own;
  CacheResult& out = result ? *result : own;
  out = {};
  // Nothing to keep: no folder, a scan answered without rays, or rays through alpha textures.
  if (folder.empty() || up_to <= 0.0f || scene.bounds.diagonal() <= 0.0f || has_zero_wall(scene) ||
      rays.has_alpha())
    return answer();
  const ClusterKey key = wall_key(scene, rays);
  const fs::path path = folder / (key.hex() + ".wall");
  std::error_code ec;
  if (fs::exists(path, ec)) {
    WallFile f{};
    std::string why;
    if (!read_wall(path, key, f, why))
      out.set(CacheOutcome::Rebuilt, why);
    else if (up_to <= f.searched) {
      out.outcome = CacheOutcome::Hit;
      fs::last_write_time(path, fs::file_time_type::clock::now(), ec); // a use
      return std::min(up_to, f.gap);
    } else {
      out.set(CacheOutcome::Rebuilt, "scanned to a shorter reach");
    }
  }
  const float gap = answer();
  std::string why;
  if (!write_atomically(
          path, [&](const fs::path& to) { return write_wall(to, key, up_to, gap); }, why))
    out.set(CacheOutcome::Unwritable, why);
  else if (out.outcome == CacheOutcome::Off)
    out.outcome = CacheOutcome::Written;
  return gap;
}

} // namespace irad
