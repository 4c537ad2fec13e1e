#pragma once
// A decoded RGBA texture in linear values, sampled bilinearly with glTF wrap modes.
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace irad {

enum class Wrap { Repeat, ClampToEdge, MirroredRepeat };

struct Texture {
  std::string name;
  int width = 0;
  int height = 0;
  std::vector<glm::vec4> texels; // row-major, row 0 is the top of the image (v = 0), linear
  Wrap wrap_s = Wrap::Repeat;
  Wrap wrap_t = Wrap::Repeat;

  // Bilinear lookup at glTF texture coordinates (u to the right, v down the image).
  glm::vec4 sample(glm::vec2 uv) const;
  // Mean of all texels (used for powers and the mean albedo).
  glm::vec4 mean() const;
};

// sRGB transfer function, decoding 8-bit-style values in [0,1] to linear.
float srgb_to_linear(float c);

} // namespace irad
