#pragma once

// Deterministic elementary functions built only from IEEE-754 basic operations (+ - * / sqrt,
// which are correctly rounded everywhere) and exact scalings. The C library's exp/log may differ
// in the last bit between platforms and library versions; random draws that pass through these
// functions must not, or the same seed would give different scenarios on different machines.
// Accuracy: within a few ulp of the true value over the whole double range.

namespace corsa::det {

/// Natural logarithm. x <= 0 gives -inf (x == 0) or NaN (x < 0), like std::log.
double log(double x);

/// e^x. Overflows to +inf, underflows to 0, like std::exp.
double exp(double x);

/// ln(Gamma(x)) for x > 0 (used by the Poisson sampler).
double lgamma(double x);

/// sin and cos for |x| up to ~1e6 (range reduction by a two-part pi/2).
double sin(double x);
double cos(double x);

}  // namespace corsa::det
