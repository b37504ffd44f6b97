#include "render/offscreen_target.h"

#include <epoxy/gl.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
#include <unistd.h>

#include "core/base/errors.h"
#include "render/render_errors.h"

namespace sublift {
namespace {

std::string framebuffer_status_name(GLenum status) {
  switch (status) {
    case GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT: return "incomplete attachment";
    case GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT: return "missing attachment";
    case GL_FRAMEBUFFER_UNSUPPORTED: return "unsupported format combination";
    case GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE: return "inconsistent multisampling";
    default: return "status 0x" + std::to_string(status);
  }
}

void check_complete(const char* what) {
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    throw RenderError(std::string("offscreen ") + what + " framebuffer incomplete: " +
                      framebuffer_status_name(status));
  }
}

// Flips bottom-up GL rows to top-down image rows and makes the image opaque.
void flip_rows_opaque(std::vector<std::uint8_t>& rgba, int width, int height) {
  const std::size_t row = static_cast<std::size_t>(width) * 4;
  for (int y = 0; y < height / 2; ++y) {
    std::swap_ranges(rgba.begin() + y * row, rgba.begin() + (y + 1) * row,
                     rgba.begin() + (height - 1 - y) * row);
  }
  for (std::size_t i = 3; i < rgba.size(); i += 4) rgba[i] = 255;
}

void append_bytes(void* context, void* data, int size) {
  auto* out = static_cast<std::vector<std::uint8_t>*>(context);
  const auto* bytes = static_cast<const std::uint8_t*>(data);
  out->insert(out->end(), bytes, bytes + size);
}

}  // namespace

OffscreenTarget::OffscreenTarget(int width, int height, int samples)
    : width_(width), height_(height), samples_(std::max(samples, 0)) {
  GLint max_size = 0;
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
  if (width < 1 || height < 1 || width > max_size || height > max_size) {
    throw RenderError("offscreen size " + std::to_string(width) + "x" + std::to_string(height) +
                      " is outside 1.." + std::to_string(max_size));
  }
  GLint max_samples = 0;
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  samples_ = std::min(samples_, static_cast<int>(max_samples));

  glGenFramebuffers(1, &draw_fbo_);
  glGenRenderbuffers(1, &color_rb_);
  glGenRenderbuffers(1, &depth_rb_);
  glBindFramebuffer(GL_FRAMEBUFFER, draw_fbo_);
  glBindRenderbuffer(GL_RENDERBUFFER, color_rb_);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples_, GL_RGBA8, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color_rb_);
  glBindRenderbuffer(GL_RENDERBUFFER, depth_rb_);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples_, GL_DEPTH_COMPONENT24, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_rb_);
  check_complete("draw");

  if (samples_ > 0) {
    glGenFramebuffers(1, &resolve_fbo_);
    glGenRenderbuffers(1, &resolve_rb_);
    glBindFramebuffer(GL_FRAMEBUFFER, resolve_fbo_);
    glBindRenderbuffer(GL_RENDERBUFFER, resolve_rb_);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, resolve_rb_);
    check_complete("resolve");
  }
  glBindRenderbuffer(GL_RENDERBUFFER, 0);
  bind();
}

OffscreenTarget::~OffscreenTarget() {
  const GLuint fbos[] = {draw_fbo_, resolve_fbo_};
  const GLuint rbs[] = {color_rb_, depth_rb_, resolve_rb_};
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDeleteFramebuffers(2, fbos);
  glDeleteRenderbuffers(3, rbs);
}

void OffscreenTarget::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, draw_fbo_);
  glViewport(0, 0, width_, height_);
}

std::vector<std::uint8_t> OffscreenTarget::read_rgba() const {
  GLuint source = draw_fbo_;
  if (samples_ > 0) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, draw_fbo_);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolve_fbo_);
    glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT,
                      GL_NEAREST);
    source = resolve_fbo_;
  }
  glBindFramebuffer(GL_READ_FRAMEBUFFER, source);
  std::vector<std::uint8_t> rgba = read_framebuffer_rgba(width_, height_);
  bind();
  return rgba;
}

std::vector<std::uint8_t> read_framebuffer_rgba(int width, int height) {
  std::vector<std::uint8_t> rgba(static_cast<std::size_t>(width) * height * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR) {
    throw RenderError("glReadPixels failed with GL error 0x" + std::to_string(error));
  }
  flip_rows_opaque(rgba, width, height);
  return rgba;
}

void write_png(const std::string& path, int width, int height,
               std::span<const std::uint8_t> rgba) {
  if (width < 1 || height < 1 ||
      rgba.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4) {
    throw IoError(path + ": cannot write PNG: pixel buffer does not match " +
                  std::to_string(width) + "x" + std::to_string(height) + " RGBA");
  }
  std::vector<std::uint8_t> encoded;
  if (!stbi_write_png_to_func(append_bytes, &encoded, width, height, 4, rgba.data(), width * 4)) {
    throw IoError(path + ": cannot encode PNG");
  }
  // Same folder as the target so the rename is atomic; pid keeps concurrent writers apart.
  const std::string temp = path + ".tmp." + std::to_string(::getpid());
  {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    if (!out) throw IoError(path + ": cannot write PNG: " + std::strerror(errno));
    out.write(reinterpret_cast<const char*>(encoded.data()),
              static_cast<std::streamsize>(encoded.size()));
    out.close();
    if (!out) {
      std::remove(temp.c_str());
      throw IoError(path + ": cannot write PNG: write failed");
    }
  }
  std::error_code error;
  std::filesystem::rename(temp, path, error);
  if (error) {
    std::remove(temp.c_str());
    throw IoError(path + ": cannot write PNG: " + error.message());
  }
}

}  // namespace sublift
