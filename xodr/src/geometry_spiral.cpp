// Clothoid (OpenDRIVE 1.8 §7.4): curvature k(σ) = k0 + c σ with c = (k1 - k0) / length, heading
// θ(σ) = k0 σ + c σ²/2, position ∫0^ds e^{iθ(σ)} dσ.
//
// Main path: the record is cut into n equal pieces of bounded heading change (series_pieces; one
// piece for usual road spirals), and each piece's integral ∫0^h e^{i(a u + b u²)} du
// (a = curvature at the piece start, b = c/2) is summed from the Taylor series of its integrand
// g(u) = e^{i(a u + b u²)}: since g' = i(a + 2bu) g, the coefficients obey
// (m+1) g_{m+1} = i (a g_m + 2b g_{m-1}). On such a piece the terms fall like 1/m! from the start,
// so ~20 terms of ~10 flops each give the integral to rounding: about 5x fewer instructions than
// the two Fresnel integrals of the closed form, and free of its cancellation when k0/c is large.
//
// Records turning more than kMaxPieces pieces' worth (loops) use the closed form instead:
// completing the square, θ = (c/2)(σ + k0/c)² - k0²/(2c), so
//   ∫0^ds e^{iθ} dσ = e^{-i k0²/(2c)} sqrt(π/|c|) [ΔC + i sign(c) ΔS]
// with Fresnel integrals at w = (σ + k0/c)·sqrt(|c|/π); when k0/c is huge both w are large and the
// difference loses digits, so such spirals are integrated by Gauss-Legendre quadrature instead, in
// pieces short enough (≤ 0.5 rad of heading each) that the quadrature is exact to rounding.

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "corsa/xodr/geometry.h"
#include "geometry_local.h"

namespace corsa::xodr {
namespace {

constexpr double kEpsilon = 2.220446049250313e-16;
// Largest rounding error (m) accepted from the Fresnel closed form before quadrature is used.
constexpr double kClosedFormTolerance = 1e-10;
// Quadrature pieces are capped: a record turning more than this is not a road (and the piece
// count must fit an int). The result stays finite, if coarse.
constexpr double kMaxQuadraturePieces = 1e6;

// Work budget of one series piece (see series_pieces): a piece then has |a|h + |b|h² ≤ 2, its
// terms stay below 2^m/m! (no digit lost to cancellation) and at most ~25 of them are needed.
constexpr double kPieceTurn = 1.0;
// Past this many pieces the closed form is cheaper than the piecewise series.
constexpr int kMaxPieces = 16;
// 1/(m+1) for the series recurrence, avoiding a division per term.
constexpr int kMaxTerms = 48;
constexpr std::array<double, kMaxTerms + 2> kInverse = [] {
  std::array<double, kMaxTerms + 2> table{};
  for (size_t m = 0; m < table.size(); ++m) {
    table[m] = 1.0 / static_cast<double>(m + 1);
  }
  return table;
}();

RefPoint spiral_by_quadrature(double k0, double c, double ds) {
  const double turn = std::abs(k0 * ds) + 0.5 * std::abs(c) * ds * ds;
  const int pieces = 1 + static_cast<int>(std::min(turn / 0.5, kMaxQuadraturePieces));
  const double step = ds / pieces;
  double x = 0.0;
  double y = 0.0;
  for (int piece = 0; piece < pieces; ++piece) {
    const double mid = (piece + 0.5) * step;
    for (size_t i = 0; i < detail::kGaussNodes.size(); ++i) {
      for (const double sign : {-1.0, 1.0}) {
        const double sigma = mid + sign * detail::kGaussNodes[i] * 0.5 * step;
        const double theta = sigma * (k0 + 0.5 * c * sigma);
        x += detail::kGaussWeights[i] * std::cos(theta);
        y += detail::kGaussWeights[i] * std::sin(theta);
      }
    }
  }
  x *= 0.5 * step;
  y *= 0.5 * step;
  return RefPoint{x, y, ds * (k0 + 0.5 * c * ds), k0 + c * ds};
}

RefPoint spiral_by_fresnel(double k0, double c, double ds) {
  const double scale = std::sqrt(std::abs(c) / std::numbers::pi);
  const double u0 = k0 / c;
  const double w0 = u0 * scale;
  const double w1 = (u0 + ds) * scale;
  // Rounding error of the closed form, in metres: the Fresnel values carry about eps·(1 + w)
  // (the phase πw²/2 of their asymptotic form), magnified by 1/scale, and the common phase
  // k0²/(2c) = πw0²/2 carries eps·w0², turning a chord of up to ds. Quadrature instead costs in
  // proportion to the heading change, so the closed form is kept wherever it is accurate: a
  // tight spiral turning hundreds of radians then costs the same as a gentle one.
  const double w_max = std::max(std::abs(w0), std::abs(w1));
  const double rounding = kEpsilon * ((1.0 + w_max) / scale + w_max * w_max * ds);
  if (rounding > kClosedFormTolerance) {
    return spiral_by_quadrature(k0, c, ds);
  }
  const Fresnel f0 = fresnel(w0);
  const Fresnel f1 = fresnel(w1);
  const double sign = c > 0.0 ? 1.0 : -1.0;
  const double dc = (f1.c - f0.c) / scale;
  const double dsn = sign * (f1.s - f0.s) / scale;
  const double phase = -0.5 * k0 * u0;  // -k0²/(2c)
  const double cp = std::cos(phase);
  const double sp = std::sin(phase);
  return RefPoint{cp * dc - sp * dsn, sp * dc + cp * dsn, ds * (k0 + 0.5 * c * ds), k0 + c * ds};
}

// ∫0^h e^{i(a u + b u²)} du and the end value e^{i(a h + b h²)}, as complex numbers (x + iy).
struct PieceIntegral {
  double x = 0.0;
  double y = 0.0;
  double end_cos = 1.0;
  double end_sin = 0.0;
};

PieceIntegral integrate_piece(double a, double b, double h) {
  // t_m = g_m h^m: t_0 = 1, t_{m+1} = i (a h t_m + 2 b h² t_{m-1}) / (m+1). The integral is
  // h Σ t_m / (m+1) and the end value Σ t_m.
  const double alpha = a * h;
  const double beta = 2.0 * b * h * h;
  // Once m+1 exceeds twice |alpha| + |beta| each term is at most half the larger of the two
  // before it, so two consecutive negligible terms bound the whole tail.
  const double decay = 2.0 * (std::abs(alpha) + std::abs(beta));
  double tr = 1.0;  // t_m
  double ti = 0.0;
  double pr = 0.0;  // t_{m-1}
  double pi = 0.0;
  PieceIntegral sum{1.0, 0.0, 1.0, 0.0};
  // Two terms per pass, so that the stopping test runs half as often.
  for (int m = 0; m < kMaxTerms; m += 2) {
    const double ur = -(alpha * ti + beta * pi) * kInverse[m];  // t_{m+1}
    const double ui = (alpha * tr + beta * pr) * kInverse[m];
    const double vr = -(alpha * ui + beta * ti) * kInverse[m + 1];  // t_{m+2}
    const double vi = (alpha * ur + beta * tr) * kInverse[m + 1];
    sum.x += ur * kInverse[m + 1] + vr * kInverse[m + 2];
    sum.y += ui * kInverse[m + 1] + vi * kInverse[m + 2];
    sum.end_cos += ur + vr;
    sum.end_sin += ui + vi;
    pr = ur;
    pi = ui;
    tr = vr;
    ti = vi;
    if (std::abs(ur) + std::abs(ui) + std::abs(vr) + std::abs(vi) < 1e-17 && m + 2 > decay) {
      break;
    }
  }
  sum.x *= h;
  sum.y *= h;
  return sum;
}

// Number of series pieces for the record up to ds, or 0 when the closed form should be used.
// The series terms of a piece starting at curvature a are bounded by those of e^{|a|u + |b|u²}, so
// |a|h + |b|h² measures its work; over n equal pieces these sum to |k0| ds + |c| ds²/2 and none
// exceeds 2/n of that sum.
int series_pieces(double k0, double c, double ds) {
  const double turn = std::abs(ds) * (std::abs(k0) + 0.5 * std::abs(c * ds));
  if (!(turn < kPieceTurn * kMaxPieces)) {
    return 0;
  }
  return 1 + static_cast<int>(turn / kPieceTurn);
}

// Sums the pieces; the start heading of each later piece is evaluated directly (not chained) so
// that rounding does not accumulate from piece to piece.
detail::LocalFrame spiral_by_series(double k0, double c, double ds, int pieces) {
  const double h = ds / pieces;
  const double b = 0.5 * c;
  double x = 0.0;
  double y = 0.0;
  double cos_end = 1.0;
  double sin_end = 0.0;
  for (int j = 0; j < pieces; ++j) {
    const double start = j * h;
    double cos_start = 1.0;
    double sin_start = 0.0;
    if (j > 0) {
      const double theta = start * (k0 + b * start);
      cos_start = std::cos(theta);
      sin_start = std::sin(theta);
    }
    const PieceIntegral piece = integrate_piece(k0 + c * start, b, h);
    x += cos_start * piece.x - sin_start * piece.y;
    y += sin_start * piece.x + cos_start * piece.y;
    cos_end = cos_start * piece.end_cos - sin_start * piece.end_sin;
    sin_end = sin_start * piece.end_cos + cos_start * piece.end_sin;
  }
  return detail::LocalFrame{RefPoint{x, y, ds * (k0 + b * ds), k0 + c * ds}, cos_end, sin_end};
}

double spiral_rate(const SpiralGeometry& spiral, double length) {
  return length > 0.0 ? (spiral.curv_end - spiral.curv_start) / length : 0.0;
}

}  // namespace

RefPoint evaluate_spiral(const SpiralGeometry& spiral, double length, double ds) {
  const double k0 = spiral.curv_start;
  const double c = spiral_rate(spiral, length);
  if (c == 0.0) {
    return evaluate_arc(ArcGeometry{k0}, ds);
  }
  const int pieces = series_pieces(k0, c, ds);
  if (pieces == 0) {
    return spiral_by_fresnel(k0, c, ds);
  }
  return spiral_by_series(k0, c, ds, pieces).point;
}

namespace detail {

LocalFrame evaluate_spiral_frame(const SpiralGeometry& spiral, double length, double ds) {
  const double k0 = spiral.curv_start;
  const double c = spiral_rate(spiral, length);
  const int pieces = c == 0.0 ? 0 : series_pieces(k0, c, ds);
  if (pieces == 0) {
    const RefPoint point = evaluate_spiral(spiral, length, ds);
    return LocalFrame{point, std::cos(point.hdg), std::sin(point.hdg)};
  }
  return spiral_by_series(k0, c, ds, pieces);
}

}  // namespace detail

}  // namespace corsa::xodr
