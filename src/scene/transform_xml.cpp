#include "transform_xml.h"

#include <cmath>

namespace quadtri {

bool lookAtMatrix(const Vec3& origin, const Vec3& target, const Vec3& up, Mat4& out) {
  const Vec3 dir = target - origin;
  if (!(dir.norm() > 0.0)) return false;
  const Vec3 d = dir.normalized();
  const Vec3 leftRaw = up.cross(d);
  // Parallel up and view direction leave the image's horizontal axis undefined.
  if (!(leftRaw.norm() > 1e-9 * up.norm())) return false;
  const Vec3 left = leftRaw.normalized();
  const Vec3 newUp = d.cross(left);
  out.setIdentity();
  out.block<3, 1>(0, 0) = left;
  out.block<3, 1>(0, 1) = newUp;
  out.block<3, 1>(0, 2) = d;
  out.block<3, 1>(0, 3) = origin;
  return true;
}

Mat4 rotationMatrix(const Vec3& axis, double degrees) {
  Mat4 m = Mat4::Identity();
  m.block<3, 3>(0, 0) = Eigen::AngleAxisd(degrees * kPi / 180.0, axis.normalized()).matrix();
  return m;
}

Vec3 parseXyz(const XmlElement& element, double fallback) {
  if (element.has("value")) {
    if (element.has("x") || element.has("y") || element.has("z"))
      element.fail("<{}> takes either 'value' or x/y/z attributes, not both", element.tag());
    const std::vector<double> v = parseNumberList(element, element.attr("value"), "value");
    if (v.size() == 1) return Vec3::Constant(v[0]);
    if (v.size() != 3)
      element.fail("<{}> value must have 1 or 3 numbers, got {}", element.tag(), v.size());
    return Vec3(v[0], v[1], v[2]);
  }
  Vec3 out = Vec3::Constant(fallback);
  const char* names[] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i)
    if (element.has(names[i])) out[i] = parseNumber(element, element.attr(names[i]), names[i]);
  return out;
}

namespace {

Vec3 parseVectorAttribute(const XmlElement& element, const char* name) {
  const std::vector<double> v = parseNumberList(element, element.required(name), name);
  if (v.size() != 3) element.fail("'{}' must have 3 numbers, got {}", name, v.size());
  return Vec3(v[0], v[1], v[2]);
}

Mat4 parseLookAt(const XmlElement& element) {
  element.checkAttributes({"origin", "target", "up"});
  const Vec3 origin = parseVectorAttribute(element, "origin");
  const Vec3 target = parseVectorAttribute(element, "target");
  Vec3 up;
  if (element.has("up")) {
    up = parseVectorAttribute(element, "up");
  } else {
    // Mitsuba 3 picks any up vector perpendicular to the view direction when none is given.
    Vec3 unusedT;
    orthonormalBasis(safeNormalized(target - origin), up, unusedT);
  }
  Mat4 m;
  if (!lookAtMatrix(origin, target, up, m))
    element.fail("<lookat> needs origin != target and an 'up' not parallel to target - origin");
  return m;
}

Mat4 parseRotate(const XmlElement& element) {
  element.checkAttributes({"angle", "axis", "value", "x", "y", "z"});
  Vec3 axis;
  if (element.has("axis")) {
    if (element.has("value") || element.has("x") || element.has("y") || element.has("z"))
      element.fail("<rotate> takes its axis from 'axis', 'value' or x/y/z, only one of them");
    axis = parseVectorAttribute(element, "axis");
  } else {
    axis = parseXyz(element, 0.0);
  }
  if (!(axis.norm() > 0.0)) element.fail("<rotate> needs a non-zero axis");
  const double angle = parseNumber(element, element.required("angle"), "angle");
  return rotationMatrix(axis, angle);
}

Mat4 parseMatrix(const XmlElement& element) {
  element.checkAttributes({"value"});
  const std::vector<double> v = parseNumberList(element, element.required("value"), "value");
  Mat4 m = Mat4::Identity();
  if (v.size() == 16) {
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) m(r, c) = v[size_t(4 * r + c)];
    if (m.row(3) != Eigen::RowVector4d(0, 0, 0, 1))
      element.fail("<matrix> must be affine: its last row must be 0 0 0 1");
  } else if (v.size() == 9) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) m(r, c) = v[size_t(3 * r + c)];
  } else {
    element.fail("<matrix> value must have 16 numbers (row-major 4x4) or 9 (3x3), got {}",
                 v.size());
  }
  return m;
}

}  // namespace

Mat4 parseTransform(const XmlElement& transform) {
  Mat4 m = Mat4::Identity();
  for (const XmlElement& child : transform.children()) {
    const std::string_view tag = child.tag();
    Mat4 step = Mat4::Identity();
    if (tag == "translate") {
      child.checkAttributes({"value", "x", "y", "z"});
      step.block<3, 1>(0, 3) = parseXyz(child, 0.0);
    } else if (tag == "scale") {
      child.checkAttributes({"value", "x", "y", "z"});
      step.diagonal().head<3>() = parseXyz(child, 1.0);
    } else if (tag == "rotate") {
      step = parseRotate(child);
    } else if (tag == "matrix") {
      step = parseMatrix(child);
    } else if (tag == "lookat") {
      step = parseLookAt(child);
    } else {
      child.fail(
          "unknown element <{}> inside <transform>; expected translate, rotate, scale, "
          "matrix or lookat",
          tag);
    }
    m = step * m;
  }
  const double det = m.block<3, 3>(0, 0).determinant();
  if (!std::isfinite(det) || std::abs(det) < 1e-300)
    transform.fail("<transform name=\"{}\"> is singular (a zero scale?)", transform.attr("name"));
  return m;
}

}  // namespace quadtri
