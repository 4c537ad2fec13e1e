#include "arrays.h"

#include "core/util/error.h"

#include <fmt/format.h>
#include <string>

namespace py = pybind11;

namespace irad::python {

FloatArray to_array(const Image& image, int channels) {
  FloatArray array({image.height(), image.width(), channels});
  auto out = array.mutable_unchecked<3>();
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x)
      for (int c = 0; c < channels; ++c) out(y, x, c) = image.at(x, y)[c];
  return array;
}

namespace {

std::string shape_text(const py::array& array) {
  std::string text = "(";
  for (py::ssize_t i = 0; i < array.ndim(); ++i)
    text += fmt::format("{}{}", i ? ", " : "", array.shape(i));
  return text + (array.ndim() == 1 ? ",)" : ")");
}

} // namespace

Image to_image(const py::array& array, const char* what) {
  if (!array.dtype().is(py::dtype::of<float>()))
    throw Error("", what,
                "must be a float32 array (numpy.float32), not " +
                    std::string(py::str(array.dtype())));
  if (array.ndim() != 3 || array.shape(0) < 1 || array.shape(1) < 1 ||
      (array.shape(2) != 3 && array.shape(2) != 4))
    throw Error("", what,
                "must have the shape (height, width, 3) or (height, width, 4), not " +
                    shape_text(array));
  const auto in = py::array_t<float, py::array::forcecast>(array).unchecked<3>();
  const int height = static_cast<int>(in.shape(0));
  const int width = static_cast<int>(in.shape(1));
  const int channels = static_cast<int>(in.shape(2));
  Image image(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      glm::vec4 p(in(y, x, 0), in(y, x, 1), in(y, x, 2), 1.0f);
      if (channels == 4) p.a = in(y, x, 3);
      image.at(x, y) = p;
    }
  return image;
}

} // namespace irad::python
