#pragma once
// A linked GLSL program built from embedded shader files, "#version 330 core" prepended.
#include <string>
#include <string_view>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace sublift {

/// Owns one program object of the current GL context; move-only.
class ShaderProgram {
 public:
  /// Compiles and links the embedded `vertex_file` and `fragment_file`; throws ShaderError
  /// with the shader's name and the GLSL log on failure.
  ShaderProgram(std::string_view vertex_file, std::string_view fragment_file);
  ~ShaderProgram();
  ShaderProgram(ShaderProgram&& other) noexcept;
  ShaderProgram& operator=(ShaderProgram&& other) noexcept;
  ShaderProgram(const ShaderProgram&) = delete;
  ShaderProgram& operator=(const ShaderProgram&) = delete;

  /// Makes this the current program.
  void use() const;
  /// Sets a uniform of the current program (this one must be in use); unknown names are ignored.
  void set(const char* name, float value) const;
  void set(const char* name, int value) const;  // samplers: the texture unit
  void set(const char* name, const glm::vec3& value) const;
  void set(const char* name, const glm::vec4& value) const;
  void set(const char* name, const glm::mat3& value) const;
  void set(const char* name, const glm::mat4& value) const;

  /// The GL program object name.
  unsigned id() const { return program_; }

 private:
  std::string name_;  // "mesh.vert+mesh.frag", for messages
  unsigned program_ = 0;
};

}  // namespace sublift
