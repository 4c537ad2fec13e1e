#pragma once
// GPU time per kind of pass (GL_TIME_ELAPSED queries, core since OpenGL 3.3). Results are read
// once, after the last pass, so timing does not stall the pipeline between passes. Only created
// when asked for: an untimed render issues no queries.
#include <array>
#include <glad/gl.h>
#include <vector>

namespace irad::gl {

class PassTimer {
public:
  enum Kind { Shadow = 0, Shading = 1, Kinds = 2 };

  explicit PassTimer(const GladGLContext& api) : api_(&api) {}
  ~PassTimer() {
    if (!queries_.empty())
      api_->DeleteQueries(static_cast<GLsizei>(queries_.size()), queries_.data());
  }
  PassTimer(const PassTimer&) = delete;
  PassTimer& operator=(const PassTimer&) = delete;

  void begin(Kind kind) {
    GLuint q = 0;
    api_->GenQueries(1, &q);
    queries_.push_back(q);
    kinds_.push_back(kind);
    api_->BeginQuery(GL_TIME_ELAPSED, q);
  }
  void end() { api_->EndQuery(GL_TIME_ELAPSED); }
  // Seconds measured elsewhere (another context's timer: raster/shadow/shadow_helpers.h).
  void add(Kind kind, double seconds) { added_[kind] += seconds; }

  // Seconds per kind; waits for every query.
  std::array<double, Kinds> seconds() const {
    std::array<double, Kinds> total = added_;
    for (std::size_t i = 0; i < queries_.size(); ++i) {
      GLuint64 ns = 0;
      api_->GetQueryObjectui64v(queries_[i], GL_QUERY_RESULT, &ns);
      total[kinds_[i]] += static_cast<double>(ns) * 1e-9;
    }
    return total;
  }

private:
  const GladGLContext* api_;
  std::vector<GLuint> queries_;
  std::vector<Kind> kinds_;
  std::array<double, Kinds> added_{};
};

} // namespace irad::gl
