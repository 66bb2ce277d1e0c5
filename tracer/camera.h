#pragma once
// The pinhole camera: rays through any point of the film, in continuous pixel coordinates.

#include "scalar.h"
#include "scene.h"

#include <cmath>

namespace tracer {

/// A pinhole camera prepared from the scene's Camera for one image size, computing in the scalar
/// type T (float for rendering, double for the reference). Film coordinates are continuous pixel
/// coordinates: (0, 0) is the top-left corner of the image, (width, height) the bottom-right one,
/// and pixel (x, y) covers [x, x+1) x [y, y+1).
template <class T>
class PinholeCameraT {
 public:
  using V = Vec3T<T>;

  /// `width` and `height` in pixels (> 0); the vertical field of view is kept, so the horizontal
  /// one follows the aspect ratio. `up` need only not be parallel to the view direction.
  PinholeCameraT(const Camera& camera, int width, int height)
      : origin_(camera.position), hither_(camera.hither), width_(width), height_(height) {
    const V forward = glm::normalize(V(camera.look_at) - V(camera.position));
    const V right_rh = glm::normalize(glm::cross(forward, V(camera.up)));
    const V true_up = glm::cross(right_rh, forward);
    // In a left-handed world (NFF, SPD) the image's right is up x view: the film is mirrored.
    const V right = camera.left_handed ? -right_rh : right_rh;
    const T half_h = std::tan(T(0.5) * T(camera.vfov_deg) * T(3.14159265358979) / T(180));
    const T half_w = half_h * T(width) / T(height);
    forward_ = forward;
    // Film-space steps per pixel: +x goes right, +y goes down.
    dx_ = right * (T(2) * half_w / T(width));
    dy_ = true_up * (T(-2) * half_h / T(height));
    corner_ = forward - right * half_w + true_up * half_h;  // direction to film point (0, 0)
  }

  /// Unit-direction ray from the eye through film point (px, py), continuous pixel coordinates.
  /// Its tmin clips at the camera's hither distance, measured along the view direction.
  RayT<T> ray_through(T px, T py) const {
    RayT<T> ray;
    ray.org = origin_;
    ray.dir = glm::normalize(corner_ + px * dx_ + py * dy_);
    if (hither_ > T(0)) ray.tmin = hither_ / glm::dot(ray.dir, forward_);
    return ray;
  }

  /// Ray through pixel (x, y) at the sub-pixel offset (jx, jy) in [0, 1); (0.5, 0.5) is the centre.
  RayT<T> primary_ray(int x, int y, float jx = 0.5f, float jy = 0.5f) const {
    return ray_through(T(float(x) + jx), T(float(y) + jy));
  }

  int width() const { return width_; }            ///< Image width, pixels.
  int height() const { return height_; }          ///< Image height, pixels.
  const V& origin() const { return origin_; }     ///< Eye point, world units.
  const V& forward() const { return forward_; }   ///< Unit view direction.

 private:
  V origin_;
  V forward_;
  V corner_;   ///< Unnormalised direction to the film's top-left corner.
  V dx_, dy_;  ///< Direction change per pixel along x (right) and y (down).
  T hither_;   ///< Near clip distance along forward_, world units.
  int width_, height_;
};

using PinholeCamera = PinholeCameraT<float>;

}  // namespace tracer
