// Fresnel reflectance of smooth interfaces, shared by the smooth and rough BSDFs.
#pragma once

#include "quadtri/math/color.h"
#include "quadtri/math/vec.h"

namespace quadtri {

/// The Fresnel split at a dielectric interface for one incident direction.
struct DielectricFresnel {
  double reflectance = 1.0;  ///< F; 1 under total internal reflection
  double cosThetaT = 0.0;    ///< signed cosine of the refracted direction (opposite side to i)
  double etaTI = 1.0;        ///< η_t / η_i, the relative IOR the refracted ray crosses
};

/// Exact unpolarized Fresnel reflectance of a dielectric interface, F = (r_s² + r_p²)/2 with
/// r_s = (η_i cos i − η_t cos t)/(η_i cos i + η_t cos t), r_p = (η_t cos i − η_i cos t)/(η_t cos i
/// + η_i cos t) and Snell's law η_i sin i = η_t sin t. `eta` = η_inside/η_outside; a negative
/// `cosThetaI` means the incident direction is inside, so η_t/η_i = 1/eta there.
DielectricFresnel fresnelDielectric(double cosThetaI, double eta);

/// Exact unpolarized Fresnel reflectance of a conductor with complex relative IOR η̃ = eta + i·k
/// per channel: the same r_s, r_p with cos t = √(1 − sin²i / η̃²) complex (pbrt-v4 §9.3.6).
Color fresnelConductor(double cosThetaI, const Color& eta, const Color& k);

/// The refracted direction in the local frame (normal +z): −w/η_ti + (w_z/η_ti + cos t)·ẑ, with
/// cosThetaT and etaTI from fresnelDielectric.
inline Vec3 refractLocal(const Vec3& w, const DielectricFresnel& fresnel) {
  const double inv = 1.0 / fresnel.etaTI;
  return Vec3(-w.x() * inv, -w.y() * inv, fresnel.cosThetaT);
}

}  // namespace quadtri
