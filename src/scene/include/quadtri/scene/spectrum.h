// Mitsuba's <spectrum> values as quadtri's linear sRGB colours.
#pragma once

#include <vector>

#include "quadtri/math/color.h"

namespace quadtri {

/// The CIE 1931 2° colour matching functions x̄, ȳ, z̄ at `nanometres`, by the multi-lobe
/// Gaussian fit of Wyman, Sloan and Shirley (2013, "Simple analytic approximations to the CIE
/// XYZ color matching functions"), within about 1% of the tabulated functions' integrals.
Color cieXyzMatching(double nanometres);

/// A sampled spectrum (wavelengths in nm, strictly increasing, with their values) as linear
/// sRGB: XYZ = ∫ S(λ)·(x̄, ȳ, z̄)(λ) dλ / ∫ ȳ(λ) dλ over 360–830 nm, S linear between samples and
/// constant beyond the first and last, converted by the XYZ → linear sRGB (D65) matrix, then
/// divided channel by channel by the colour of the constant spectrum 1 (the equal-energy white
/// maps to (1, 1, 1), so a flat spectrum of value v gives the grey v, as in an RGB renderer).
Color spectrumToRgb(const std::vector<double>& nanometres, const std::vector<double>& values);

}  // namespace quadtri
