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

} // namespace irad::gl
