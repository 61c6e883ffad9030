#include "border_solver.h"

#include <algorithm>
#include <cmath>

namespace corsa::ngii::detail {
namespace {

constexpr double kCentreTolerance = 0.02;  // m: centre error the weights are raised to reach

/// Solves the dense system a x = b in place (partial pivoting); n is small (lanes + 1).
void solve_dense(double* a, std::vector<double>& b, size_t n) {
  for (size_t col = 0; col < n; ++col) {
    size_t pivot = col;
    for (size_t row = col + 1; row < n; ++row) {
      if (std::abs(a[row * n + col]) > std::abs(a[pivot * n + col])) {
        pivot = row;
      }
    }
    for (size_t k = 0; k < n; ++k) {
      std::swap(a[col * n + k], a[pivot * n + k]);
    }
    std::swap(b[col], b[pivot]);
    for (size_t row = col + 1; row < n; ++row) {
      const double f = a[row * n + col] / a[col * n + col];
      for (size_t k = col; k < n; ++k) {
        a[row * n + k] -= f * a[col * n + k];
      }
      b[row] -= f * b[col];
    }
  }
  for (size_t row = n; row-- > 0;) {
    for (size_t k = row + 1; k < n; ++k) {
      b[row] -= a[row * n + k] * b[k];
    }
    b[row] /= a[row * n + row];
  }
}

}  // namespace

void narrow_inside_of_turn(std::vector<LaneTarget>& lanes, double curvature, double clearance,
                           double min_width) {
  if (lanes.empty() || std::abs(curvature) < 1e-9) {
    return;
  }
  // The centre of curvature at t = 1 / curvature; the outermost lane on that side.
  const double radius = 1.0 / std::abs(curvature);
  LaneTarget& lane = curvature < 0.0 ? lanes.back() : lanes.front();
  if (!lane.centred) {
    return;
  }
  // Distance from the lane's centre towards the turn's centre, less the clearance.
  const double room = (curvature < 0.0 ? lane.centre + radius : radius - lane.centre) - clearance;
  lane.width = std::min(lane.width, std::max(2.0 * room, min_width));
}

std::vector<double> solve_borders(const std::vector<LaneTarget>& lanes, size_t reference) {
  const size_t count = lanes.size();
  const size_t n = count + 1;
  // One workspace: centre weights alpha, width weights beta, matrix a (GCC 12 mis-reports
  // -Wfree-nonheap-object on several small vectors here).
  std::vector<double> work(2 * count + n * n, 0.0);
  double* alpha = work.data();
  double* beta = alpha + count;
  double* a = beta + count;
  for (size_t k = 0; k < count; ++k) {
    alpha[k] = lanes[k].centred ? 100.0 : 0.0;
    beta[k] = lanes[k].centred ? 1.0 : 1e4;
  }
  std::vector<double> b(n);
  for (int round = 0; round < 5; ++round) {
    std::fill(a, a + n * n, 0.0);
    std::fill(b.begin(), b.end(), 0.0);
    // Keeps the reference lane's inner border near zero (it takes the reference line error).
    a[reference * n + reference] += 0.01;
    for (size_t k = 0; k < count; ++k) {
      // Residuals: alpha ((b_k + b_{k+1}) / 2 - c)^2 + beta (b_k - b_{k+1} - m)^2.
      const double w = alpha[k];
      const double v = beta[k];
      const double c = lanes[k].centre;
      const double m = lanes[k].width;
      a[k * n + k] += w / 4 + v;
      a[k * n + k + 1] += w / 4 - v;
      a[(k + 1) * n + k] += w / 4 - v;
      a[(k + 1) * n + k + 1] += w / 4 + v;
      b[k] += w * c / 2 + v * m;
      b[k + 1] += w * c / 2 - v * m;
    }
    solve_dense(a, b, n);
    bool done = true;
    for (size_t k = 0; k < count; ++k) {
      if (lanes[k].centred &&
          std::abs(0.5 * (b[k] + b[k + 1]) - lanes[k].centre) > kCentreTolerance) {
        alpha[k] *= 10.0;
        done = false;
      }
    }
    if (done) {
      break;
    }
  }
  return b;
}

}  // namespace corsa::ngii::detail
