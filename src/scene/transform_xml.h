// <transform> elements: Mitsuba 3's translate/rotate/scale/matrix/lookat, composed in order.
#pragma once

#include "quadtri/math/vec.h"
#include "xml_file.h"

namespace quadtri {

/// Camera-to-world matrix looking from `origin` towards `target`: columns (up×d, d×(up×d), d,
/// origin) with d the unit view direction, so local +z maps to d (Mitsuba's look_at). Returns
/// false when the direction is zero or parallel to `up`.
bool lookAtMatrix(const Vec3& origin, const Vec3& target, const Vec3& up, Mat4& out);

/// Rotation by `degrees` about `axis` (right-handed, Rodrigues' formula).
Mat4 rotationMatrix(const Vec3& axis, double degrees);

/// The product T_k ··· T_1 of the <transform> element's children T_1..T_k (each later child is
/// applied after the earlier ones, as in Mitsuba 3). Throws on unknown children, bad numbers or
/// a singular result.
Mat4 parseTransform(const XmlElement& transform);

/// Three components from `value="x, y, z"` (or one value for all three) or from x/y/z
/// attributes, each missing one being `fallback` (Mitsuba's point/vector/translate/scale).
Vec3 parseXyz(const XmlElement& element, double fallback);

}  // namespace quadtri
