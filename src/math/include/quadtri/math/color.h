// Linear RGB radiance and reflectance.
#pragma once

#include <Eigen/Core>

namespace quadtri {

using Color = Eigen::Array3d;

inline double luminance(const Color& c) {
  return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
}
inline bool isBlack(const Color& c) {
  return (c == 0.0).all();
}

}  // namespace quadtri
