#include "raster/context/gl_objects.h"

#include "core/util/error.h"

namespace irad::gl {

void fill_buffer(const GladGLContext& api, GLenum target, std::size_t bytes, GLenum usage,
                 const std::function<void(void*)>& fill, const char* what) {
  api.BufferData(target, static_cast<GLsizeiptr>(bytes), nullptr, usage);
  if (bytes == 0) return;
  void* storage = api.MapBufferRange(target, 0, static_cast<GLsizeiptr>(bytes),
                                     GL_MAP_WRITE_BIT | GL_MAP_INVALIDATE_BUFFER_BIT);
  if (storage == nullptr) throw Error("", what, "cannot map a buffer to fill it");
  try {
    fill(storage);
  } catch (...) {
    api.UnmapBuffer(target);
    throw;
  }
  if (api.UnmapBuffer(target) == GL_FALSE)
    throw Error("", what, "a buffer's data was lost while it was written");
}

void fill_buffer_range(const GladGLContext& api, GLuint buffer, std::size_t offset,
                       std::size_t bytes, const std::function<void(void*)>& fill,
                       const char* what) {
  if (bytes == 0) return;
  api.BindBuffer(GL_COPY_WRITE_BUFFER, buffer);
  void* storage = api.MapBufferRange(
      GL_COPY_WRITE_BUFFER, static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes),
      GL_MAP_WRITE_BIT | GL_MAP_INVALIDATE_RANGE_BIT | GL_MAP_UNSYNCHRONIZED_BIT);
  if (storage == nullptr) {
    api.BindBuffer(GL_COPY_WRITE_BUFFER, 0);
    throw Error("", what, "cannot map a buffer to fill it");
  }
  try {
    fill(storage);
  } catch (...) {
    api.UnmapBuffer(GL_COPY_WRITE_BUFFER);
    api.BindBuffer(GL_COPY_WRITE_BUFFER, 0);
    throw;
  }
  const bool kept = api.UnmapBuffer(GL_COPY_WRITE_BUFFER) != GL_FALSE;
  api.BindBuffer(GL_COPY_WRITE_BUFFER, 0);
  if (!kept) throw Error("", what, "a buffer's data was lost while it was written");
}

} // namespace irad::gl
