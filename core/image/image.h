#pragma once
// A linear float RGBA image, row 0 at the top.
#include <cstddef>
#include <glm/glm.hpp>
#include <vector>

namespace irad {

class Image {
public:
  Image() = default;
  Image(int width, int height) : width_(width), height_(height), pixels_(area(width, height)) {}

  int width() const { return width_; }
  int height() const { return height_; }
  glm::vec4& at(int x, int y) { return pixels_[index(x, y)]; }
  const glm::vec4& at(int x, int y) const { return pixels_[index(x, y)]; }
  std::vector<glm::vec4>& pixels() { return pixels_; }
  const std::vector<glm::vec4>& pixels() const { return pixels_; }
  std::size_t non_finite_count() const; // pixels with a NaN or Inf channel

private:
  static std::size_t area(int w, int h) { return static_cast<std::size_t>(w) * h; }
  std::size_t index(int x, int y) const { return static_cast<std::size_t>(y) * width_ + x; }
  int width_ = 0;
  int height_ = 0;
  std::vector<glm::vec4> pixels_;
};

} // namespace irad
