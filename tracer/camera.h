#pragma once
// The pinhole camera: rays through any point of the film, in continuous pixel coordinates.

#include "scene.h"

#include <cmath>

namespace tracer {

/// A pinhole camera prepared from the scene's Camera for one image size. Film coordinates are
/// continuous pixel coordinates: (0, 0) is the top-left corner of the image, (width, height) the
/// bottom-right one, and pixel (x, y) covers [x, x+1) x [y, y+1).
class PinholeCamera {
 public:
  /// `width` and `height` in pixels (> 0); the vertical field of view is kept, so the horizontal
  /// one follows the aspect ratio. `up` need only not be parallel to the view direction.
  PinholeCamera(const Camera& camera, int width, int height)
      : origin_(camera.position), hither_(camera.hither), width_(width), height_(height) {
    const Vec3 forward = glm::normalize(camera.look_at - camera.position);
    const Vec3 right_rh = glm::normalize(glm::cross(forward, camera.up));
    const Vec3 true_up = glm::cross(right_rh, forward);
    // In a left-handed world (NFF, SPD) the image's right is up x view: the film is mirrored.
    const Vec3 right = camera.left_handed ? -right_rh : right_rh;
    const float half_h = std::tan(0.5f * camera.vfov_deg * 3.14159265358979f / 180.0f);
    const float half_w = half_h * float(width) / float(height);
    forward_ = forward;
    // Film-space steps per pixel: +x goes right, +y goes down.
    dx_ = right * (2.0f * half_w / float(width));
    dy_ = true_up * (-2.0f * half_h / float(height));
    corner_ = forward - right * half_w + true_up * half_h;  // direction to film point (0, 0)
  }

  /// Unit-direction ray from the eye through film point (px, py), continuous pixel coordinates.
  /// Its tmin clips at the camera's hither distance, measured along the view direction.
  Ray ray_through(float px, float py) const {
    Ray ray;
    ray.org = origin_;
    ray.dir = glm::normalize(corner_ + px * dx_ + py * dy_);
    if (hither_ > 0.0f) ray.tmin = hither_ / glm::dot(ray.dir, forward_);
    return ray;
  }

  /// Ray through pixel (x, y) at the sub-pixel offset (jx, jy) in [0, 1); (0.5, 0.5) is the centre.
  Ray primary_ray(int x, int y, float jx = 0.5f, float jy = 0.5f) const {
    return ray_through(float(x) + jx, float(y) + jy);
  }

  int width() const { return width_; }              ///< Image width, pixels.
  int height() const { return height_; }            ///< Image height, pixels.
  const Vec3& origin() const { return origin_; }    ///< Eye point, world units.
  const Vec3& forward() const { return forward_; }  ///< Unit view direction.

 private:
  Vec3 origin_;
  Vec3 forward_;
  Vec3 corner_;   ///< Unnormalised direction to the film's top-left corner.
  Vec3 dx_, dy_;  ///< Direction change per pixel along x (right) and y (down).
  float hither_;  ///< Near clip distance along forward_, world units.
  int width_, height_;
};

}  // namespace tracer
