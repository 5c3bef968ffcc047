#include "quadtri/surface/robust_quadric_fit.h"

#include <Eigen/QR>

namespace quadtri {
namespace {

using Coeffs = Eigen::Matrix<double, 10, 1>;
// A null space of the hard rows: 10 coefficients by at most 10 directions.
using NullBasis = Eigen::Matrix<double, 10, Eigen::Dynamic, 0, 10, 10>;
using Row = Eigen::Matrix<double, 1, 10>;

// The fit works on w = (A, B, C, D/√2, E/√2, F/√2, G, H, I, J): the Euclidean norm of w is the
// Frobenius norm of the quadric's 4×4 matrix (up to the linear part's factor 2), which is
// invariant under rotations, so damping and least squares do not depend on the axes.
const double kSqrt2 = std::sqrt(2.0);

// Damping of the tangency solve relative to its O(1) rows in the local frame: it only acts on
// directions the data do not determine (flat data), with a bias of (μ/σ)² elsewhere.
constexpr double kTangencyDamping = 1e-8;
// Damping of the choice of λ in q + λL²: Σ L(m)⁴ is ~(h/8R)⁴ for curvature radius R, so this
// acts only where the arc midpoints lie within ~1e-6 edge lengths of the plane.
constexpr double kPencilDamping2 = 1e-24;
// Below this share of Σ n_k·∇q(v_k) at one corner the fit counts as turned against the normal.
constexpr double kLeastCornerShare = 0.05;

// Row r with r·w = q(y).
Row valueRow(const Vec3& y) {
  Row r;
  r << y.x() * y.x(), y.y() * y.y(), y.z() * y.z(), kSqrt2 * y.x() * y.y(), kSqrt2 * y.x() * y.z(),
      kSqrt2 * y.y() * y.z(), y.x(), y.y(), y.z(), 1.0;
  return r;
}

// Row r with r·w = ∇q(y)·t.
Row gradientRow(const Vec3& y, const Vec3& t) {
  Row r;
  r << 2 * y.x() * t.x(), 2 * y.y() * t.y(), 2 * y.z() * t.z(),
      kSqrt2 * (y.y() * t.x() + y.x() * t.y()), kSqrt2 * (y.z() * t.x() + y.x() * t.z()),
      kSqrt2 * (y.z() * t.y() + y.y() * t.z()), t.x(), t.y(), t.z(), 0.0;
  return r;
}

Vec3 gradientOf(const Coeffs& w, const Vec3& y) {
  return Vec3(gradientRow(y, Vec3::UnitX()).dot(w), gradientRow(y, Vec3::UnitY()).dot(w),
              gradientRow(y, Vec3::UnitZ()).dot(w));
}

// q(y) = [y;1]ᵀ Q [y;1].
Mat4 matrixOf(const Coeffs& w) {
  const double d = w[3] / kSqrt2, e = w[4] / kSqrt2, f = w[5] / kSqrt2;
  Mat4 Q;
  Q << w[0], d, e, 0.5 * w[6],  //
      d, w[1], f, 0.5 * w[7],   //
      e, f, w[2], 0.5 * w[8],   //
      0.5 * w[6], 0.5 * w[7], 0.5 * w[8], w[9];
  return Q;
}

QuadricCoeffs coefficientsOf(const Mat4& Q, double scale = 1.0) {
  QuadricCoeffs q = {Q(0, 0),     Q(1, 1),     Q(2, 2),     2 * Q(0, 1), 2 * Q(0, 2),
                     2 * Q(1, 2), 2 * Q(0, 3), 2 * Q(1, 3), 2 * Q(2, 3), Q(3, 3)};
  for (double& c : q) c *= scale;
  return q;
}

double norm(const QuadricCoeffs& q) {
  double norm2 = 0.0;
  for (double c : q) norm2 += c * c;
  return std::sqrt(norm2);
}

// Fallback for a triangle without extent: the plane through its point with the mean normal.
QuadricFit pointFit(const CornerData& data) {
  const Vec3 n = safeNormalized(data.normal[0] + data.normal[1] + data.normal[2], data.normal[0]);
  const Vec3& p = data.position[0];
  QuadricFit fit;
  fit.pointFallback = true;
  Mat4 Q = Mat4::Zero();
  Q.block<3, 1>(0, 3) = 0.5 * n;
  Q.block<1, 3>(3, 0) = 0.5 * n.transpose();
  Q(3, 3) = -n.dot(p);
  fit.q = coefficientsOf(Q, 1.0 / norm(coefficientsOf(Q)));
  for (const Vec3& nk : data.normal)
    fit.cornerNormalErrorDeg = std::max(fit.cornerNormalErrorDeg, angleDegrees(n, nk));
  return fit;
}

// Steps (1) and (2) of fitQuadric in the local frame: w, and the null space of the hard rows
// (the directions (3) may still move in). perCorner replaces the normalisation's sum by one
// row per corner. False when the hard rows vanish or contradict each other. The matrices of
// varying size have fixed capacities: no allocation per fit.
bool solveTangency(const std::array<Vec3, 3>& y, const std::array<Vec3, 3>& normal, bool perCorner,
                   Coeffs& w, NullBasis& nullBasis) {
  Eigen::Matrix<double, 6, 10> H = Eigen::Matrix<double, 6, 10>::Zero();
  Eigen::Matrix<double, 6, 1> rhs = Eigen::Matrix<double, 6, 1>::Zero();
  for (int k = 0; k < 3; ++k) {
    H.row(k) = valueRow(y[k]);
    if (perCorner) {
      H.row(3 + k) = gradientRow(y[k], normal[k]);
      rhs[3 + k] = 1.0 / 3.0;
    } else {
      H.row(3) += gradientRow(y[k], normal[k]);
      rhs[3] = 1.0;
    }
  }
  // The hard rows' row space and null space from a column-pivoted QR of Hᵀ: Hᵀ P = Q R, so
  // Pᵀ H = Rᵀ Qᵀ. The first `rank` columns of Q span H's rows, the others its null space, and
  // the solution of least norm is Q₁ z with R₁₁ᵀ z = (Pᵀ rhs) on the first `rank` rows.
  const Eigen::ColPivHouseholderQR<Eigen::Matrix<double, 10, 6>> hardQr(H.transpose());
  const Eigen::Matrix<double, 10, 6>& R = hardQr.matrixQR();
  const double r0 = std::abs(R(0, 0));
  int rank = 0;
  while (rank < 6 && std::abs(R(rank, rank)) > 1e-12 * r0) ++rank;
  if (rank == 0) return false;
  const Eigen::Matrix<double, 10, 10> Q = hardQr.householderQ();
  Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1> z(rank);
  for (int i = 0; i < rank; ++i) {
    double sum = rhs[hardQr.colsPermutation().indices()[i]];
    for (int j = 0; j < i; ++j) sum -= R(j, i) * z[j];
    z[i] = sum / R(i, i);
  }
  const Coeffs particular = Q.leftCols(rank) * z;
  // Per-corner rows can contradict each other (a repeated corner with opposite normals).
  if ((H * particular - rhs).norm() > 1e-9 * rhs.norm()) return false;
  nullBasis = Q.rightCols(10 - rank);

  // Tangency: the gradient's tangential part at each corner, damped least squares on the null
  // space of the hard rows (particular ⟂ that null space, so damping pulls toward it):
  // min |T(particular + N a)|² + μ²|a|², the least squares of [T N; μ I] a = [−T particular; 0].
  Eigen::Matrix<double, 6, 10> T;
  for (int k = 0; k < 3; ++k) {
    Vec3 t1, t2;
    orthonormalBasis(normal[k], t1, t2);
    T.row(2 * k) = gradientRow(y[k], t1);
    T.row(2 * k + 1) = gradientRow(y[k], t2);
  }
  const Eigen::Index free = nullBasis.cols();
  using Stacked = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 16, 10>;
  Stacked damped = Stacked::Zero(6 + free, free);
  damped.topRows(6) = T * nullBasis;
  damped.bottomRows(free).diagonal().setConstant(kTangencyDamping);
  Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 16, 1> target =
      Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 16, 1>::Zero(6 + free);
  target.head(6) = -(T * particular);
  const Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 10, 1> a =
      Eigen::HouseholderQR<Stacked>(damped).solve(target);
  w = particular + nullBasis * a;
  return true;
}

}  // namespace

Vec3 edgeArcMidpoint(const Vec3& vi, const Vec3& ni, const Vec3& vj, const Vec3& nj) {
  const Vec3 e = vj - vi;
  const double len = e.norm();
  const Vec3 mid = 0.5 * (vi + vj);
  if (!(len > 0.0)) return mid;
  const Vec3 ehat = e / len;
  const Vec3 nm = ni + nj;
  const Vec3 side = nm - nm.dot(ehat) * ehat;
  const double sideLen = side.norm();
  if (!(sideLen > 1e-12)) return mid;
  const Vec3 d = side / sideLen;
  // Angle of each tangent line above the chord, measured inside the edge plane.
  const double ti = std::atan2(-ni.dot(ehat), ni.dot(d));
  const double tj = std::atan2(nj.dot(ehat), nj.dot(d));
  const double theta = std::clamp(0.5 * (ti + tj), -0.5 * kPi, 0.5 * kPi);
  return mid + 0.5 * len * std::tan(0.5 * theta) * d;
}

QuadricFit fitQuadric(const CornerData& data) {
  const std::array<Vec3, 3>& v = data.position;
  const Vec3 centre = (v[0] + v[1] + v[2]) / 3.0;
  const double scale = ((v[1] - v[0]).norm() + (v[2] - v[1]).norm() + (v[0] - v[2]).norm()) / 3.0;
  if (!(scale > 0.0) || !std::isfinite(scale)) return pointFit(data);

  std::array<Vec3, 3> y, m;
  for (int k = 0; k < 3; ++k) {
    y[k] = (v[k] - centre) / scale;
    m[k] = (data.arcMidpoint[k] - centre) / scale;
  }

  // (1)+(2); if the least-squares tangency turns a corner's gradient against its normal
  // (normals no quadric comes near, e.g. averaged across parts that pass through each other),
  // (1) fixes every corner's normal component instead: n_k·∇q(v_k) = 1/3.
  Coeffs w;
  NullBasis nullBasis;
  if (!solveTangency(y, data.normal, false, w, nullBasis)) return pointFit(data);
  double least = kInfinity, sum = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double along = gradientOf(w, y[k]).dot(data.normal[k]);
    least = std::min(least, along);
    sum += along;
  }
  Coeffs corner;
  NullBasis cornerNull;
  if (least < kLeastCornerShare * sum && solveTangency(y, data.normal, true, corner, cornerNull)) {
    w = corner;
    nullBasis = cornerNull;
  }

  // (3) The member of the pencil w + λL² through the arc midpoints (least squares in λ).
  const Vec3 face =
      safeNormalized((y[1] - y[0]).cross(y[2] - y[0]),
                     safeNormalized(data.normal[0] + data.normal[1] + data.normal[2]));
  const Coeffs plane2 = (Coeffs() << face.x() * face.x(), face.y() * face.y(), face.z() * face.z(),
                         kSqrt2 * face.x() * face.y(), kSqrt2 * face.x() * face.z(),
                         kSqrt2 * face.y() * face.z(), 0, 0, 0, 0)
                            .finished();
  // L² meets the hard rows already unless the triangle has no plane (collinear corners); then
  // its projection onto them does. Otherwise evaluate L(m)² as a square: through the 10-term
  // row, flat data would leave ~1e-16 of round-off that the damping could not tell from shape.
  const Coeffs pencil = nullBasis * (nullBasis.transpose() * plane2);
  const bool planar = (pencil - plane2).norm() < 1e-12;
  double num = 0.0, den = kPencilDamping2;
  for (int k = 0; k < 3; ++k) {
    const double l2 = planar ? face.dot(m[k]) * face.dot(m[k]) : valueRow(m[k]).dot(pencil);
    num += valueRow(m[k]).dot(w) * l2;
    den += l2 * l2;
  }
  w -= (num / den) * pencil;

  QuadricFit fit;
  for (int k = 0; k < 3; ++k)
    fit.cornerNormalErrorDeg =
        std::max(fit.cornerNormalErrorDeg, angleDegrees(gradientOf(w, y[k]), data.normal[k]));

  // Back to world coordinates: y = (x − centre)/scale, so with S = [I, −centre; 0, scale] the
  // world matrix is Sᵀ Q S (the factor scale² > 0 keeps the orientation).
  Mat4 S = Mat4::Identity();
  S.block<3, 1>(0, 3) = -centre;
  S(3, 3) = scale;
  const Mat4 world = S.transpose() * matrixOf(w) * S;
  const double unit = 1.0 / norm(coefficientsOf(world));
  fit.q = coefficientsOf(world, unit);
  fit.pencil = coefficientsOf(S.transpose() * matrixOf(pencil) * S, unit);
  return fit;
}

}  // namespace quadtri
