#pragma once
// Parts of one render (docs/cluster.md): `irad render --path-range A:B` (raster, rt-vpl) or
// `--spp-range A:B` (pt) renders the paths (samples) A..B-1 of the full N-path (S-sample) render
// into an EXR whose header says what it is (irad.* string attributes, below). Convention: a part
// holds its paths' light with the full render's weights (1/n_j of the N-path walk; 1/S per
// sample), and the part that starts at 0 also holds the visible emitters and the background, so
// the full image is the plain sum of the parts (alpha too: 1 in total). merge_parts checks that
// the parts belong together and cover 0..N exactly once, and sums them in double precision.
#include "core/image/image.h"
#include "core/image/image_io.h"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace irad {

struct PartInfo {
  std::string kind;        // "paths" (--path-range) or "spp" (--spp-range)
  std::uint32_t total = 0; // N, or S
  std::uint32_t first = 0; // the range first..end-1
  std::uint32_t end = 0;
  std::string scene_file; // as given (informational)
  std::string scene_hash; // FNV-1a 64 of the scene file's bytes, 16 hex digits
  std::string options;    // every option that changes the image, canonical (see render_command)
  std::string version;    // irad's
};

// The range A:B, or the share of a task of an array: "auto" takes task t of k from
// SLURM_ARRAY_TASK_ID - SLURM_ARRAY_TASK_MIN (MIN 0 when unset) and SLURM_ARRAY_TASK_COUNT and
// gives it [floor(t total / k), floor((t + 1) total / k)). Throws irad::Error naming `option`
// unless 0 <= A < B <= total (the range is not empty and lies in 0..total).
std::pair<std::uint32_t, std::uint32_t> parse_part_range(const std::string& text,
                                                         std::uint32_t total, const char* option);

// FNV-1a 64 of the file's bytes as 16 hex digits. Throws irad::Error naming the file.
std::string file_hash(const std::filesystem::path& path);
// irad's version, "0.1".
const char* irad_version();

// The header of a part, and back. part_info throws irad::Error naming `file` when an attribute
// is missing or malformed (an EXR that is not a part of irad's).
ExrAttributes part_attributes(const PartInfo& part);
PartInfo part_info(const ExrAttributes& attributes, const std::string& file);

// Reads the parts, refuses (irad::Error naming the file) one of another scene, options, version,
// kind, total or size, an overlap or a gap in the ranges (a missing part), and returns the sum
// of their pixels (double precision, rounded to float once) with the header of the whole range.
struct MergedImage {
  Image image;
  PartInfo info; // the parts' info with the range 0..total
};
MergedImage merge_parts(const std::vector<std::string>& files);

} // namespace irad
