#include "render/viewport_renderer.h"

#include <epoxy/gl.h>

namespace sublift {

void ViewportRenderer::draw(const OrbitCamera& camera, const ViewportRect& rect,
                            const DisplayOptions& options) const {
  glViewport(rect.x, rect.y, rect.width, rect.height);
  glEnable(GL_SCISSOR_TEST);
  glScissor(rect.x, rect.y, rect.width, rect.height);
  glDepthMask(GL_TRUE);
  glClear(GL_DEPTH_BUFFER_BIT);
  background_.draw();
  mesh_.draw(camera, options);
  glDisable(GL_SCISSOR_TEST);
}

void clear_framebuffer(int width, int height, const glm::vec3& color) {
  glViewport(0, 0, width, height);
  glDisable(GL_SCISSOR_TEST);
  glDepthMask(GL_TRUE);
  glClearColor(color.r, color.g, color.b, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

void frame_bounds(OrbitCamera& camera, const Bounds& bounds) {
  if (bounds.empty) {
    camera.frame(glm::dvec3(-0.5), glm::dvec3(0.5));
  } else {
    camera.frame(bounds.min, bounds.max);
  }
}

}  // namespace sublift
