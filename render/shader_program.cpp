#include "render/shader_program.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <glm/gtc/type_ptr.hpp>
#include <string>
#include <utility>

#include "render/embedded_shaders.h"
#include "render/render_errors.h"

namespace sublift {
namespace {

constexpr std::string_view kVersionLine = "#version 330 core\n";

std::string shader_log(GLuint shader) {
  GLint length = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
  glGetShaderInfoLog(shader, length, nullptr, log.data());
  return log.c_str();
}

std::string program_log(GLuint program) {
  GLint length = 0;
  glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
  glGetProgramInfoLog(program, length, nullptr, log.data());
  return log.c_str();
}

GLuint compile(GLenum stage, std::string_view file) {
  std::string_view body;
  try {
    body = embedded_shader(file);
  } catch (const std::exception& e) {
    throw ShaderError("shader " + std::string(file) + ": " + e.what());
  }
  // Line 1 of the file stays line 1 in the log: "#line 1" follows the version line.
  const std::string source = std::string(kVersionLine) + "#line 1\n" + std::string(body);
  const char* text = source.c_str();
  const GLuint shader = glCreateShader(stage);
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    const std::string log = shader_log(shader);
    glDeleteShader(shader);
    throw ShaderError("shader " + std::string(file) + " failed to compile:\n" + log);
  }
  return shader;
}

}  // namespace

ShaderProgram::ShaderProgram(std::string_view vertex_file, std::string_view fragment_file)
    : name_(std::string(vertex_file) + "+" + std::string(fragment_file)) {
  const GLuint vertex = compile(GL_VERTEX_SHADER, vertex_file);
  GLuint fragment = 0;
  try {
    fragment = compile(GL_FRAGMENT_SHADER, fragment_file);
  } catch (...) {
    glDeleteShader(vertex);
    throw;
  }
  program_ = glCreateProgram();
  glAttachShader(program_, vertex);
  glAttachShader(program_, fragment);
  glLinkProgram(program_);
  glDeleteShader(vertex);
  glDeleteShader(fragment);
  GLint ok = GL_FALSE;
  glGetProgramiv(program_, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    const std::string log = program_log(program_);
    glDeleteProgram(program_);
    program_ = 0;
    throw ShaderError("shader program " + name_ + " failed to link:\n" + log);
  }
}

ShaderProgram::~ShaderProgram() {
  if (program_ != 0) glDeleteProgram(program_);
}

ShaderProgram::ShaderProgram(ShaderProgram&& other) noexcept
    : name_(std::move(other.name_)), program_(std::exchange(other.program_, 0)) {}

ShaderProgram& ShaderProgram::operator=(ShaderProgram&& other) noexcept {
  if (this != &other) {
    if (program_ != 0) glDeleteProgram(program_);
    name_ = std::move(other.name_);
    program_ = std::exchange(other.program_, 0);
  }
  return *this;
}

void ShaderProgram::use() const { glUseProgram(program_); }

void ShaderProgram::set(const char* name, float value) const {
  glUniform1f(glGetUniformLocation(program_, name), value);
}

void ShaderProgram::set(const char* name, int value) const {
  glUniform1i(glGetUniformLocation(program_, name), value);
}

void ShaderProgram::set(const char* name, const glm::vec3& value) const {
  glUniform3fv(glGetUniformLocation(program_, name), 1, glm::value_ptr(value));
}

void ShaderProgram::set(const char* name, const glm::vec4& value) const {
  glUniform4fv(glGetUniformLocation(program_, name), 1, glm::value_ptr(value));
}

void ShaderProgram::set(const char* name, const glm::mat3& value) const {
  glUniformMatrix3fv(glGetUniformLocation(program_, name), 1, GL_FALSE, glm::value_ptr(value));
}

void ShaderProgram::set(const char* name, const glm::mat4& value) const {
  glUniformMatrix4fv(glGetUniformLocation(program_, name), 1, GL_FALSE, glm::value_ptr(value));
}

}  // namespace sublift
