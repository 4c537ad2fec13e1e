#include "raster/context/gl_objects.h"

#include "core/util/error.h"

namespace irad::gl {

namespace {

// Maps bytes [offset, offset + bytes) of the buffer bound to `target` with `access` (write-only
// flags), lets fill write them and unmaps; throws as fill_buffer.
void write_mapped(const GladGLContext& api, GLenum target, std::size_t offset, std::size_t bytes,
                  GLbitfield access, const std::function<void(void*)>& fill, const char* what) {
  void* storage = api.MapBufferRange(target, static_cast<GLintptr>(offset),
                                     static_cast<GLsizeiptr>(bytes), access);
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

} // namespace

void fill_buffer(const GladGLContext& api, GLenum target, std::size_t bytes, GLenum usage,
                 const std::function<void(void*)>& fill, const char* what) {
  api.BufferData(target, static_cast<GLsizeiptr>(bytes), nullptr, usage);
  if (bytes == 0) return;
  write_mapped(api, target, 0, bytes, GL_MAP_WRITE_BIT | GL_MAP_INVALIDATE_BUFFER_BIT, fill, what);
}

void fill_buffer_range(const GladGLContext& api, GLuint buffer, std::size_t offset,
                       std::size_t bytes, const std::function<void(void*)>& fill,
                       const char* what) {
  if (bytes == 0) return;
  api.BindBuffer(GL_COPY_WRITE_BUFFER, buffer);
  try {
    write_mapped(api, GL_COPY_WRITE_BUFFER, offset, bytes,
                 GL_MAP_WRITE_BIT | GL_MAP_INVALIDATE_RANGE_BIT | GL_MAP_UNSYNCHRONIZED_BIT, fill,
                 what);
  } catch (...) {
    api.BindBuffer(GL_COPY_WRITE_BUFFER, 0);
    throw;
  }
  api.BindBuffer(GL_COPY_WRITE_BUFFER, 0);
}

} // namespace irad::gl
