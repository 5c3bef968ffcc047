// <bsdf type="conductor"><string name="material" value="Au"/></bsdf>  <!-- or rgb eta, k -->
#pragma once

#include "quadtri/scene/plugin.h"

namespace quadtri {

struct ConductorIor;

/// A conductor's complex index of refraction as a scene gives it: a named metal, or "none" and
/// the explicit eta and k (Mitsuba's default eta = 0, k = 1 is a perfect mirror).
struct ConductorSpec {
  std::string material = "none";
  Color eta = Color::Zero();
  Color k = Color::Ones();

  /// " material=NAME" or " eta=[...] k=[...]".
  std::string toString() const;
  /// The RGB eta and k (lookupConductor for a named metal; an unknown one throws Error).
  ConductorIor resolve() const;
};

/// Reads specular_reflectance (white only), material, eta and k, as conductor and
/// roughconductor take them.
ConductorSpec parseConductorSpec(ObjectProperties& props);

/// A smooth conductor (render/bsdf/conductor.h).
struct ConductorBsdfParams final : BsdfParams {
  ConductorSpec conductor;

  std::string toString() const override;
  std::shared_ptr<const Bsdf> build(
      const std::vector<std::shared_ptr<const Bsdf>>& earlier) const override;
  /// The layout of quadtri 0.1.0's render keys (legacy_key.h).
  void addToKey(KeyWriter& key, std::string_view type) const override;
};

std::shared_ptr<const BsdfParams> parseConductorBsdf(ObjectProperties& props,
                                                     SceneParseState& state);

}  // namespace quadtri
