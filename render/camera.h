#pragma once
// Orbit camera: pure math, no GL. Angles live in an orbit frame that is Y-up; `up_axis` maps it
// to the world, so Y-up models (the OBJ/glTF convention) and Z-up ones (Blender's) both stand
// upright. In the orbit frame the eye sits at
// `target + distance * (cos(pitch) sin(yaw), sin(pitch), cos(pitch) cos(yaw))`: yaw 0, pitch 0
// is the front view, yaw +90 degrees the right view, pitch +90 degrees the top view (screen-up
// pointing to the back), as Blender's numpad 1/3/7 show them. With Z up the front view looks
// along +Y, exactly as in Blender.
// Mouse amounts are in viewport pixels, so the same drag feels the same at any zoom.
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace sublift {

enum class ViewPreset { Front, Back, Right, Left, Top, Bottom, ThreeQuarter };

enum class UpAxis { Y, Z };

struct OrbitCamera {
  glm::dvec3 target{0.0};
  double distance = 5.0;
  double yaw = 0.6108652381980153;    // radians about +Y; default 35 degrees (3/4 view)
  double pitch = 0.4363323129985824;  // radians in [-pi/2, pi/2]; default 25 degrees
  double fov_y = 0.7853981633974483;  // radians (45 degrees), also sets the ortho scale
  bool orthographic = false;
  UpAxis up_axis = UpAxis::Y;
  glm::dvec3 scene_center{0.0};     // bounding sphere of what is drawn, for near/far planes
  double scene_radius = 1.0;
  int viewport_width = 1;           // pixels
  int viewport_height = 1;

  static constexpr double kOrbitRadiansPerPixel = 0.01;
  static constexpr double kZoomFactorPerStep = 1.0 / 0.85;  // distance shrinks 15% per step

  /// Width / height of the viewport.
  double aspect() const;
  /// Sets the viewport size in pixels (clamped to at least 1x1).
  void set_viewport(int width, int height);
  /// Unit vector from the eye towards the target.
  glm::dvec3 forward() const;
  /// Screen-right unit vector in world space.
  glm::dvec3 right() const;
  /// Screen-up unit vector in world space.
  glm::dvec3 up() const;
  /// Eye position in world space.
  glm::dvec3 eye() const;
  /// World -> eye matrix (right-handed, looking down -Z).
  glm::dmat4 view() const;
  /// Eye -> clip matrix for the current viewport aspect; near/far enclose the scene sphere.
  glm::dmat4 projection() const;

  /// Keeps the view direction and moves target/distance so the whole box is in view (with a
  /// small margin) in both perspective and orthographic projection.
  void frame(const glm::dvec3& bbox_min, const glm::dvec3& bbox_max);
  /// Turntable rotation by a mouse drag of (dx, dy) pixels (y down): dragging right turns the
  /// model right, dragging down tips its top towards the viewer.
  void orbit(double dx, double dy);
  /// Moves the target so the point under the cursor follows a drag of (dx, dy) pixels (y down).
  void pan(double dx, double dy);
  /// Dollies towards the target; positive steps zoom in (one wheel notch is one step).
  void zoom(double steps);
  /// Looks at the target from a preset direction, keeping target and distance.
  void set_view(ViewPreset preset);
  /// World units per viewport pixel at the target's depth.
  double world_per_pixel() const;
  /// The world's up direction (+Y or +Z).
  glm::dvec3 world_up() const;
};

}  // namespace sublift
