#include "quadtri/render/bsdf/ggx.h"

#include <cmath>

namespace quadtri {

double GgxDistribution::D(const Vec3& m) const {
  if (m.z() <= 0.0) return 0.0;
  const double a2 = alpha_ * alpha_;
  const double t = m.z() * m.z() * (a2 - 1.0) + 1.0;
  return a2 / (kPi * t * t);
}

double GgxDistribution::lambda(const Vec3& w) const {
  const double z2 = w.z() * w.z();
  if (z2 == 0.0) return kInfinity;
  // α² tan²θ = α² (x² + y²) / z², computed without forming 1 − z² (it cancels near the pole).
  const double a2Tan2 = alpha_ * alpha_ * (w.x() * w.x() + w.y() * w.y()) / z2;
  return 0.5 * (std::sqrt(1.0 + a2Tan2) - 1.0);
}

Vec3 GgxDistribution::sampleVisible(const Vec3& wi, const Vec2& u) const {
  // Stretch wi to the configuration of roughness 1, where visible normals are uniform over the
  // projected hemisphere seen from wi.
  const Vec3 v = Vec3(alpha_ * wi.x(), alpha_ * wi.y(), wi.z()).normalized();
  const double lenSq = v.x() * v.x() + v.y() * v.y();
  const Vec3 t1 = lenSq > 0.0 ? Vec3(-v.y(), v.x(), 0.0) / std::sqrt(lenSq) : Vec3(1.0, 0.0, 0.0);
  const Vec3 t2 = v.cross(t1);
  // A uniform disk point, its lower half squashed onto the part of the disk the hemisphere's
  // projection covers when seen at an angle.
  const double r = std::sqrt(u.x());
  const double phi = 2.0 * kPi * u.y();
  const double p1 = r * std::cos(phi);
  double p2 = r * std::sin(phi);
  const double s = 0.5 * (1.0 + v.z());
  p2 = (1.0 - s) * std::sqrt(std::max(0.0, 1.0 - p1 * p1)) + s * p2;
  const Vec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0, 1.0 - p1 * p1 - p2 * p2)) * v;
  // Unstretch; the normal transforms with the inverse transpose of the stretch.
  return Vec3(alpha_ * nh.x(), alpha_ * nh.y(), std::max(0.0, nh.z())).normalized();
}

double GgxDistribution::pdfVisible(const Vec3& wi, const Vec3& m) const {
  const double cosIM = wi.dot(m);
  if (cosIM <= 0.0 || wi.z() <= 0.0) return 0.0;
  return G1(wi) * cosIM * D(m) / wi.z();
}

}  // namespace quadtri
