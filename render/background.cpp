#include "render/background.h"

#include <epoxy/gl.h>

#include "render/shader_program.h"

namespace sublift {

BackgroundRenderer::BackgroundRenderer()
    : program_(std::make_unique<ShaderProgram>("background.vert", "background.frag")) {
  glGenVertexArrays(1, &vao_);
}

BackgroundRenderer::~BackgroundRenderer() { glDeleteVertexArrays(1, &vao_); }

void BackgroundRenderer::draw() const {
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  glDisable(GL_BLEND);
  program_->use();
  program_->set("u_top_color", kTopColor);
  program_->set("u_bottom_color", kBottomColor);
  glBindVertexArray(vao_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glUseProgram(0);
  glDepthMask(GL_TRUE);
}

}  // namespace sublift
