#include "quadtri/render/emitter/mesh_area_emitter.h"

#include <fmt/format.h>

#include <algorithm>

#include "quadtri/math/error.h"
#include "quadtri/render/sampling/warp.h"

namespace quadtri {

MeshAreaEmitter::MeshAreaEmitter(std::shared_ptr<const TriangleMesh> mesh, const Color& radiance)
    : mesh_(std::move(mesh)), radiance_(radiance) {
  if (!radiance.allFinite() || (radiance < 0.0).any())
    fail("area emitter: expected a finite, non-negative radiance");
  cdf_.reserve(mesh_->triangleCount());
  for (size_t t = 0; t < mesh_->triangleCount(); ++t) {
    totalArea_ += 0.5 * mesh_->faceCross(t).norm();
    cdf_.push_back(totalArea_);
  }
  if (!(totalArea_ > 0.0) || !std::isfinite(totalArea_))
    fail("area emitter: the shape has no area ({} triangles)", mesh_->triangleCount());
  for (double& c : cdf_) c /= totalArea_;
}

std::optional<LightSample> MeshAreaEmitter::sampleLi(const Vec3& ref, const Vec2& u) const {
  // Pick a triangle with the first uniform, then rescale it to [0,1) to reuse for the point.
  const size_t t = size_t(std::upper_bound(cdf_.begin(), cdf_.end() - 1, u.x()) - cdf_.begin());
  const double lo = t == 0 ? 0.0 : cdf_[t - 1];
  const double width = cdf_[t] - lo;
  const double ux = width > 0.0 ? std::min((u.x() - lo) / width, 1.0 - 0x1.0p-53) : 0.0;
  const Vec2 b = squareToUniformTriangle(Vec2(ux, u.y()));
  const Vec3 point = (1.0 - b.x() - b.y()) * mesh_->corner(t, 0) + b.x() * mesh_->corner(t, 1) +
                     b.y() * mesh_->corner(t, 2);
  const Vec3 normal = mesh_->faceNormal(t);
  const Vec3 toLight = point - ref;
  const double dist2 = toLight.squaredNorm();
  if (!(dist2 > 0.0)) return std::nullopt;
  LightSample s;
  s.distance = std::sqrt(dist2);
  s.direction = toLight / s.distance;
  const double cosLight = -normal.dot(s.direction);
  if (!(cosLight > 0.0)) return std::nullopt;
  s.pdf = dist2 / (totalArea_ * cosLight);
  s.radiance = radiance_;
  s.point = point;
  s.normal = normal;
  return s;
}

double MeshAreaEmitter::pdfLi(const Vec3& ref, const Vec3& direction, const Vec3& lightPoint,
                              const Vec3& lightNormal) const {
  const double cosLight = std::abs(lightNormal.dot(direction));
  if (!(cosLight > 0.0)) return 0.0;
  return (lightPoint - ref).squaredNorm() / (totalArea_ * cosLight);
}

Color MeshAreaEmitter::eval(const Vec3& normal, const Vec3& w) const {
  return normal.dot(w) > 0.0 ? radiance_ : Color::Zero();
}

double MeshAreaEmitter::power(const Bounds3&) const {
  return kPi * luminance(radiance_) * totalArea_;
}

std::string MeshAreaEmitter::toString() const {
  return fmt::format("area(radiance=[{}, {}, {}], triangles={}, area={})", radiance_[0],
                     radiance_[1], radiance_[2], mesh_->triangleCount(), totalArea_);
}

}  // namespace quadtri
