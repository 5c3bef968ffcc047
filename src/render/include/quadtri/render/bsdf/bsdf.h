// The BSDF interface. All directions are unit vectors in the local shading frame (z = normal)
// and point away from the surface: wi towards where the path came from, wo towards where it goes.
#pragma once

#include <optional>
#include <string>

#include "quadtri/math/color.h"
#include "quadtri/math/vec.h"

namespace quadtri {

/// A sampled outgoing direction and its Monte Carlo weight f·|cos θo| / pdf.
struct BsdfSample {
  Vec3 wo;
  Color weight;
  double pdf = 0.0;    ///< solid-angle density; for delta lobes the discrete probability
  bool delta = false;  ///< sampled from a Dirac lobe (eval/pdf are zero for such directions)
  double eta = 1.0;    ///< relative IOR crossed (1 for reflection), for Russian roulette
};

class Bsdf {
 public:
  virtual ~Bsdf() = default;
  /// f(wi, wo)·|cos θo|; zero for Dirac lobes.
  virtual Color eval(const Vec3& wi, const Vec3& wo) const = 0;
  /// Solid-angle density with which sample() picks wo given wi (zero for Dirac lobes).
  virtual double pdf(const Vec3& wi, const Vec3& wo) const = 0;
  /// Samples wo from two uniform numbers `u` and one for choosing a lobe.
  virtual std::optional<BsdfSample> sample(const Vec3& wi, const Vec2& u, double uLobe) const = 0;
  /// True when every lobe is a Dirac delta (no next-event estimation through it).
  virtual bool isDelta() const = 0;
  /// Whether the surface transmits light (dielectrics): both sides are then valid.
  virtual bool transmits() const { return false; }
  /// The parameters in Mitsuba syntax, for error messages and logs.
  virtual std::string toString() const = 0;
};

}  // namespace quadtri
