#include "semantic_edge_vo/common/camera.h"

#include <cmath>
#include <sstream>

namespace semantic_edge_vo {

PinholeCamera PinholeCamera::scaled(double scale) const {
  PinholeCamera level;
  level.fx = fx * scale;
  level.fy = fy * scale;
  // Pixel centres map to pixel centres: u_level = scale * (u + 0.5) - 0.5.
  level.cx = scale * (cx + 0.5) - 0.5;
  level.cy = scale * (cy + 0.5) - 0.5;
  level.width = static_cast<int>(std::lround(width * scale));
  level.height = static_cast<int>(std::lround(height * scale));
  return level;
}

std::string PinholeCamera::validate() const {
  std::ostringstream error;
  if (!(std::isfinite(fx) && std::isfinite(fy) && fx > 0.0 && fy > 0.0))
    error << "focal lengths must be positive and finite (fx = " << fx << ", fy = " << fy << ")";
  else if (!(std::isfinite(cx) && std::isfinite(cy)))
    error << "principal point must be finite (cx = " << cx << ", cy = " << cy << ")";
  else if (width <= 0 || height <= 0)
    error << "image size must be positive (" << width << "x" << height << ")";
  return error.str();
}

PinholeCamera kittiCamera() {
  PinholeCamera camera;
  camera.fx = 718.856;
  camera.fy = 718.856;
  camera.cx = 607.1928;
  camera.cy = 185.2157;
  camera.width = 1241;
  camera.height = 376;
  return camera;
}

}  // namespace semantic_edge_vo
