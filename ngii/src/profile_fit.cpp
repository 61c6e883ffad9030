// Greedy fit of cubic pieces to a sampled profile (elevation §8.4.1, lane width §9.5.2,
// laneOffset §9.3). The first piece has all four coefficients free; later pieces inherit the
// value (and the slope, when that reaches as far) from the previous piece's end. Each piece is
// grown over as many samples as the tolerance allows, then the simplest form that still fits is
// kept.

#include <algorithm>
#include <cmath>

#include "corsa/ngii/curve_fit.h"

namespace corsa::ngii {
namespace {

/// Least squares in the scaled variable x = (s - s0) / h over the free coefficients `free`
/// (indices into a, b, c, d); fixed coefficients keep their values. Returns false when singular.
bool least_squares(std::span<const ProfileSample> samples, double s0, double h, const bool free[4],
                   double coef[4]) {
  int index[4];
  int n = 0;
  for (int k = 0; k < 4; ++k) {
    if (free[k]) {
      index[n++] = k;
    }
  }
  if (n == 0) {
    return true;
  }
  double ata[4][4] = {};
  double atb[4] = {};
  for (const ProfileSample& sample : samples) {
    const double x = (sample.s - s0) / h;
    const double powers[4] = {1.0, x, x * x, x * x * x};
    double rhs = sample.v;
    for (int k = 0; k < 4; ++k) {
      if (!free[k]) {
        rhs -= coef[k] * powers[k];
      }
    }
    for (int a = 0; a < n; ++a) {
      atb[a] += powers[index[a]] * rhs;
      for (int b = 0; b < n; ++b) {
        ata[a][b] += powers[index[a]] * powers[index[b]];
      }
    }
  }
  // Gaussian elimination with partial pivoting on the n x n system.
  for (int col = 0; col < n; ++col) {
    int pivot = col;
    for (int row = col + 1; row < n; ++row) {
      if (std::abs(ata[row][col]) > std::abs(ata[pivot][col])) {
        pivot = row;
      }
    }
    if (std::abs(ata[pivot][col]) < 1e-12) {
      return false;
    }
    std::swap(ata[col], ata[pivot]);
    std::swap(atb[col], atb[pivot]);
    for (int row = col + 1; row < n; ++row) {
      const double f = ata[row][col] / ata[col][col];
      for (int k = col; k < n; ++k) {
        ata[row][k] -= f * ata[col][k];
      }
      atb[row] -= f * atb[col];
    }
  }
  for (int row = n - 1; row >= 0; --row) {
    for (int k = row + 1; k < n; ++k) {
      atb[row] -= ata[row][k] * atb[k];
    }
    atb[row] /= ata[row][row];
  }
  for (int a = 0; a < n; ++a) {
    coef[index[a]] = atb[a];
  }
  return true;
}

struct Piece {
  bool ok = false;
  xodr::Poly3 poly;
  double max_error = 0.0;
};

/// Fits samples [i0, j] with `degree` (0..3); `start` fixes value and slope when given.
Piece fit_piece(std::span<const ProfileSample> samples, size_t i0, size_t j, int degree,
                const xodr::Poly3* start, double tolerance, bool free_slope = false) {
  Piece piece;
  // No more free coefficients than samples can determine.
  degree = std::min(degree, static_cast<int>(j - i0) + (start == nullptr || free_slope ? 0 : 1));
  const double s0 = samples[i0].s;
  const double h = std::max(samples[j].s - s0, 1e-9);
  // Scaled coefficients: v = A + B x + C x^2 + D x^3 with x = (s - s0) / h.
  double coef[4] = {0.0, 0.0, 0.0, 0.0};
  bool free[4] = {true, degree >= 1, degree >= 2, degree >= 3};
  if (start != nullptr) {
    coef[0] = start->value(s0);
    coef[1] = start->slope(s0) * h;
    free[0] = false;
    free[1] = free_slope && degree >= 1;
  }
  const auto range = samples.subspan(i0, j - i0 + 1);
  if (!least_squares(range, s0, h, free, coef)) {
    return piece;
  }
  piece.poly = xodr::Poly3{s0, coef[0], coef[1] / h, coef[2] / (h * h), coef[3] / (h * h * h)};
  bool banded = true;
  for (size_t k = 0; k < range.size(); ++k) {
    const ProfileSample& sample = range[k];
    piece.max_error = std::max(piece.max_error, std::abs(piece.poly.value(sample.s) - sample.v));
    // Between samples the cubic must stay within the band the two samples span (plus the
    // tolerance): no overshoot where nothing was measured.
    if (k + 1 < range.size()) {
      const ProfileSample& next = range[k + 1];
      const double mid = piece.poly.value(0.5 * (sample.s + next.s));
      banded = banded && mid >= std::min(sample.v, next.v) - tolerance &&
               mid <= std::max(sample.v, next.v) + tolerance;
    }
  }
  piece.ok = std::isfinite(piece.max_error) && piece.max_error <= tolerance && banded;
  return piece;
}

/// The longest piece from sample i0 (galloping, then binary search on the last sample), then
/// the simplest form that covers the same samples. `slope` keeps the previous piece's slope as
/// well as its value. `good` receives the index of the last sample covered.
Piece longest_piece(std::span<const ProfileSample> samples, size_t i0, const xodr::Poly3* previous,
                    double tolerance, bool slope, size_t& good) {
  const size_t last = samples.size() - 1;
  // Value continuity only: the previous value as a constant start, the slope left free.
  xodr::Poly3 value_only;
  const xodr::Poly3* start = previous;
  if (previous != nullptr && !slope) {
    value_only = xodr::Poly3{samples[i0].s, previous->value(samples[i0].s), 0.0, 0.0, 0.0};
    start = &value_only;
  }
  const bool free_slope = previous != nullptr && !slope;
  auto attempt = [&](size_t j, int degree) {
    return fit_piece(samples, i0, j, degree, start, tolerance, free_slope);
  };
  Piece best = attempt(i0 + 1, 3);
  good = i0 + 1;
  size_t bad = last + 1;
  for (size_t span = 2; good < last;) {
    const size_t j = std::min(last, i0 + span);
    Piece piece = attempt(j, 3);
    if (!piece.ok) {
      bad = j;
      break;
    }
    best = piece;
    good = j;
    span *= 2;
  }
  while (bad - good > 1) {
    const size_t j = good + (bad - good) / 2;
    Piece piece = attempt(j, 3);
    if (piece.ok) {
      best = piece;
      good = j;
    } else {
      bad = j;
    }
  }
  for (int degree = start == nullptr || free_slope ? 0 : 1; degree < 3; ++degree) {
    Piece simple = attempt(good, degree);
    if (simple.ok) {
      return simple;
    }
  }
  return best;
}

}  // namespace

ProfileFit fit_profile(std::span<const ProfileSample> samples, double tolerance) {
  ProfileFit result;
  if (samples.empty()) {
    return result;
  }
  if (samples.size() == 1) {
    result.pieces.push_back(xodr::Poly3{samples[0].s, samples[0].v, 0.0, 0.0, 0.0});
    return result;
  }
  const size_t last = samples.size() - 1;
  size_t i0 = 0;
  while (i0 < last) {
    const xodr::Poly3* previous = result.pieces.empty() ? nullptr : &result.pieces.back();
    // Value and slope continue the previous piece (C1) when that reaches as far as a piece
    // with a free slope (C0 at the joint); greedy C1 alone can ring on noisy samples.
    size_t good = i0 + 1;
    Piece best = longest_piece(samples, i0, previous, tolerance, true, good);
    if (previous != nullptr) {
      size_t good_c0 = i0 + 1;
      Piece c0 = longest_piece(samples, i0, previous, tolerance, false, good_c0);
      if ((c0.ok && !best.ok) || (c0.ok == best.ok && good_c0 > good)) {
        best = c0;
        good = good_c0;
      }
    }
    result.max_error = std::max(result.max_error, best.max_error);
    result.pieces.push_back(best.poly);
    i0 = good;
  }
  // A piece whose value and slope continue the previous one unchanged adds nothing.
  std::vector<xodr::Poly3> merged;
  for (const xodr::Poly3& piece : result.pieces) {
    if (!merged.empty()) {
      const xodr::Poly3& prev = merged.back();
      if (prev.c == 0.0 && prev.d == 0.0 && piece.c == 0.0 && piece.d == 0.0 && piece.b == prev.b) {
        continue;
      }
    }
    merged.push_back(piece);
  }
  result.pieces = std::move(merged);
  return result;
}

}  // namespace corsa::ngii
