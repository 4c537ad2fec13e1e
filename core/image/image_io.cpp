// EXR and PNG files. Every failure (OpenEXR's Iex exceptions, stb's 0 returns, I/O errors) leaves
// as one irad::Error "FILE: cannot read: REASON" / "FILE: cannot write: REASON" on one line.
// Writers go through FILE.tmp in the same folder and rename it over FILE, so FILE is either the
// complete new file or left as it was; the .tmp is removed on failure.
#include "core/image/image_io.h"

#include "core/util/error.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStdIO.h>
#include <ImfStringAttribute.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <stdexcept>
#include <system_error>
#include <vector>

// Static functions, and no stdio writer (it ignores fwrite/fclose errors): we write the bytes.
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#define STBI_WRITE_NO_STDIO
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wold-style-cast"
#pragma GCC diagnostic ignored "-Wunused-function"
#include <stb_image_write.h>
#pragma GCC diagnostic pop

namespace irad {

namespace fs = std::filesystem;

namespace {

static_assert(sizeof(glm::vec4) == 4 * sizeof(float), "Image pixels must be 4 packed floats");

constexpr const char* kChannels[4] = {"R", "G", "B", "A"};

// A library message on one line.
std::string one_line(std::string s) {
  std::replace_if(
      s.begin(), s.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

// The current errno as text, or `fallback` when errno is not set.
std::string errno_reason(const char* fallback) {
  return errno != 0 ? std::generic_category().message(errno) : std::string(fallback);
}

// Throws unless the image can be written: non-empty, with width * height pixels.
void check_image(const fs::path& path, const Image& image) {
  if (image.width() <= 0 || image.height() <= 0)
    throw Error(path.string(), "", "cannot write: the image is empty");
  if (image.pixels().size() != static_cast<std::size_t>(image.width()) * image.height())
    throw Error(path.string(), "", "cannot write: the image has the wrong number of pixels");
}

// Throws unless the folder that will hold `path` exists (an empty parent is the current folder).
void check_output_folder(const fs::path& path) {
  const fs::path folder = path.parent_path();
  std::error_code ec;
  if (folder.empty() || fs::is_directory(folder, ec)) return;
  const bool exists = fs::exists(folder, ec);
  throw Error(path.string(), "",
              "output folder '" + folder.string() +
                  (exists ? "' is not a folder" : "' does not exist"));
}

// Runs write_tmp(path + ".tmp") and renames the result to `path`. write_tmp reports failure by
// throwing any std::exception; its what() becomes the reason of "cannot write: <reason>".
// An existing `path` that is not a regular file (a folder, a device) is refused, not replaced.
template <class WriteTmp>
void write_via_tmp(const fs::path& path, WriteTmp&& write_tmp) {
  check_output_folder(path);
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (fs::exists(status) && !fs::is_regular_file(status))
    throw Error(path.string(), "", "cannot write: it exists and is not a regular file");
  fs::path tmp = path;
  tmp += ".tmp";
  std::string reason;
  try {
    write_tmp(tmp);
    fs::rename(tmp, path, ec);
    if (!ec) return;
    reason = ec.message();
  } catch (const std::exception& e) {
    reason = one_line(e.what());
  } catch (...) {
    reason = "unknown error";
  }
  if (fs::is_regular_file(fs::symlink_status(tmp, ec))) fs::remove(tmp, ec);
  throw Error(path.string(), "", "cannot write: " + reason);
}

// Opens `path` for binary writing; throws std::runtime_error with the OS reason.
std::ofstream open_output(const fs::path& path) {
  errno = 0;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw std::runtime_error(errno_reason("cannot create the file"));
  return out;
}

// Flushes and closes `out`; throws when any write into it failed (errno is kept from the
// failing call, open_output cleared it).
void close_output(std::ofstream& out) {
  out.close();
  if (!out) throw std::runtime_error(errno_reason("write error"));
}

} // namespace

ImageFormat image_format_of(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".exr") return ImageFormat::Exr;
  if (ext == ".png") return ImageFormat::Png;
  throw Error(path.string(), "",
              "unknown image type '" + path.extension().string() + "' (use .exr or .png)");
}

void write_image(const fs::path& path, const Image& image, const PngOptions& png) {
  switch (image_format_of(path)) {
  case ImageFormat::Exr:
    write_exr(path, image);
    return;
  case ImageFormat::Png:
    write_png(path, image, png);
    return;
  }
}

// Channels R, G, B, A as 32-bit FLOAT, ZIP compression, data window = display window at (0, 0).
void write_exr(const fs::path& path, const Image& image, const ExrAttributes& attributes) {
  check_image(path, image);
  write_via_tmp(path, [&image, &attributes](const fs::path& tmp) {
    Imf::Header header(image.width(), image.height());
    header.compression() = Imf::ZIP_COMPRESSION;
    for (const auto& [name, value] : attributes) header.insert(name, Imf::StringAttribute(value));
    Imf::FrameBuffer frame;
    const float* first = &image.pixels().front().x;
    const std::size_t x_stride = sizeof(glm::vec4);
    const std::size_t y_stride = x_stride * static_cast<std::size_t>(image.width());
    for (int c = 0; c < 4; ++c) {
      header.channels().insert(kChannels[c], Imf::Channel(Imf::FLOAT));
      frame.insert(kChannels[c], Imf::Slice::Make(Imf::FLOAT, first + c, header.dataWindow(),
                                                  x_stride, y_stride));
    }
    std::ofstream out = open_output(tmp);
    {
      Imf::StdOFStream stream(out, tmp.c_str());
      Imf::OutputFile file(stream, header);
      file.setFrameBuffer(frame);
      file.writePixels(image.height());
    } // ~OutputFile writes the line offset table and swallows errors: they stay in out's state
    close_output(out);
  });
}

// 8-bit sRGB RGB (alpha is dropped): byte = round(255 * linear_to_srgb(tone_map(channel))).
void write_png(const fs::path& path, const Image& image, const PngOptions& png) {
  check_image(path, image);
  const int width = image.width();
  const int height = image.height();
  if (width > INT_MAX / 3) throw Error(path.string(), "", "cannot write: the image is too wide");
  std::vector<unsigned char> rgb(image.pixels().size() * 3);
  std::size_t i = 0;
  for (const glm::vec4& p : image.pixels())
    for (int c = 0; c < 3; ++c)
      rgb[i++] =
          static_cast<unsigned char>(std::lround(255.0f * linear_to_srgb(tone_map(p[c], png))));

  write_via_tmp(path, [&](const fs::path& tmp) {
    std::vector<char> encoded;
    auto append = [](void* context, void* data, int size) {
      const char* bytes = static_cast<const char*>(data);
      static_cast<std::vector<char>*>(context)->insert(
          static_cast<std::vector<char>*>(context)->end(), bytes, bytes + size);
    };
    if (stbi_write_png_to_func(append, &encoded, width, height, 3, rgb.data(), width * 3) == 0)
      throw std::runtime_error("PNG encoding failed");
    std::ofstream out = open_output(tmp);
    out.write(encoded.data(), static_cast<std::streamsize>(encoded.size()));
    close_output(out);
  });
}

// The image covers the data window (its min corner becomes pixel (0, 0)); the display window is
// ignored. R, G and B must exist; A is read when present, else 1. Half, float and uint channels
// are all converted to float by OpenEXR.
Image read_exr(const fs::path& path, ExrAttributes* attributes) {
  try {
    errno = 0;
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(errno_reason("cannot open the file"));
    Imf::StdIFStream stream(in, path.c_str());
    Imf::InputFile file(stream);
    const Imf::Header& header = file.header();
    for (int c = 0; c < 3; ++c)
      if (header.channels().findChannel(kChannels[c]) == nullptr)
        throw std::runtime_error(std::string("no '") + kChannels[c] + "' channel");
    const Imath::Box2i window = header.dataWindow();
    const std::int64_t width = std::int64_t{window.max.x} - window.min.x + 1;
    const std::int64_t height = std::int64_t{window.max.y} - window.min.y + 1;
    if (width <= 0 || height <= 0 || width > INT_MAX || height > INT_MAX)
      throw std::runtime_error("invalid data window");
    Image image(static_cast<int>(width), static_cast<int>(height));
    Imf::FrameBuffer frame;
    const float* first = &image.pixels().front().x;
    const std::size_t x_stride = sizeof(glm::vec4);
    const std::size_t y_stride = x_stride * static_cast<std::size_t>(width);
    for (int c = 0; c < 4; ++c)
      frame.insert(kChannels[c], Imf::Slice::Make(Imf::FLOAT, first + c, window, x_stride, y_stride,
                                                  1, 1, c == 3 ? 1.0 : 0.0));
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
    if (attributes != nullptr)
      for (auto a = header.begin(); a != header.end(); ++a)
        if (const auto* text = dynamic_cast<const Imf::StringAttribute*>(&a.attribute()))
          (*attributes)[a.name()] = text->value();
    return image;
  } catch (const std::exception& e) {
    throw Error(path.string(), "", "cannot read: " + one_line(e.what()));
  }
}

// Returns a value in [0, 1]; negatives, zero and NaN give 0, +Inf gives 1.
float tone_map(float linear, const PngOptions& png) {
  const float x = linear * std::exp2(png.exposure);
  if (!(x > 0.0f)) return 0.0f;
  if (png.tone_map == ToneMap::Reinhard) return std::isinf(x) ? 1.0f : x / (1.0f + x);
  return std::min(x, 1.0f);
}

// The sRGB OETF of c clamped to [0, 1] (NaN gives 0).
float linear_to_srgb(float c) {
  if (!(c > 0.0f)) return 0.0f;
  if (c >= 1.0f) return 1.0f;
  return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

} // namespace irad
