#pragma once

// Linear RGB colours: radiance in relative units (1 = a white surface facing the noon sun on a
// clear day) or reflectance (0..1 per channel).

#include <cmath>
#include <cstdint>

namespace corsa::sensors {

struct Color {
  double r = 0.0, g = 0.0, b = 0.0;
};
inline Color operator+(Color a, Color b) { return {a.r + b.r, a.g + b.g, a.b + b.b}; }
inline Color operator*(Color a, double s) { return {a.r * s, a.g * s, a.b * s}; }
inline Color operator*(Color a, Color b) { return {a.r * b.r, a.g * b.g, a.b * b.b}; }
inline Color mix(Color a, Color b, double t) { return a * (1.0 - t) + b * t; }
inline bool operator==(Color a, Color b) { return a.r == b.r && a.g == b.g && a.b == b.b; }

/// Linear value of an 8-bit sRGB-encoded channel (the gamma-2.2 approximation the renderer
/// uses for every colour it reads).
inline double linear_from_srgb8(uint8_t c) { return std::pow(c / 255.0, 2.2); }
/// Linear colour of an 8-bit sRGB triple.
inline Color linear_rgb(uint8_t r, uint8_t g, uint8_t b) {
  return {linear_from_srgb8(r), linear_from_srgb8(g), linear_from_srgb8(b)};
}

}  // namespace corsa::sensors
