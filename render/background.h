#pragma once
// The viewport's backdrop: a vertical light grey-blue gradient.
#include <memory>

#include <glm/vec3.hpp>

namespace sublift {

class ShaderProgram;

/// Fills the current viewport with the gradient; needs a current GL 3.3 context.
class BackgroundRenderer {
 public:
  static constexpr glm::vec3 kTopColor{0.78f, 0.81f, 0.86f};
  static constexpr glm::vec3 kBottomColor{0.56f, 0.60f, 0.67f};

  /// Compiles the background shaders; throws ShaderError.
  BackgroundRenderer();
  ~BackgroundRenderer();
  BackgroundRenderer(const BackgroundRenderer&) = delete;
  BackgroundRenderer& operator=(const BackgroundRenderer&) = delete;

  /// Draws the gradient over the whole current viewport without touching depth.
  void draw() const;

 private:
  std::unique_ptr<ShaderProgram> program_;
  unsigned vao_ = 0;  // empty: core profile needs a bound VAO even without attributes
};

}  // namespace sublift
