#include "positions/geo_reference.h"

#include <cmath>
#include <numbers>
#include <vector>

#include "corsa/core/strings.h"

namespace corsa::engine::detail {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

struct Token {
  std::string_view key;
  std::string_view value;
};

std::vector<Token> tokens(std::string_view text) {
  std::vector<Token> out;
  size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() &&
           (text[i] == ' ' || text[i] == '\t' || text[i] == '\n' || text[i] == '\r')) {
      ++i;
    }
    const size_t start = i;
    while (i < text.size() && text[i] != ' ' && text[i] != '\t' && text[i] != '\n' &&
           text[i] != '\r') {
      ++i;
    }
    std::string_view word = text.substr(start, i - start);
    if (word.empty()) {
      continue;
    }
    if (word.front() == '+') {
      word.remove_prefix(1);
    }
    const size_t eq = word.find('=');
    out.push_back(eq == std::string_view::npos ? Token{word, {}}
                                               : Token{word.substr(0, eq), word.substr(eq + 1)});
  }
  return out;
}

}  // namespace

std::optional<TransverseMercator> parse_simple_projection(std::string_view proj) {
  TransverseMercator tm;
  std::string_view kind;
  std::optional<int> zone;
  bool south = false;
  for (const Token& token : tokens(proj)) {
    const auto number = parse_double(token.value);
    if (token.key == "proj") {
      kind = token.value;
    } else if (token.key == "ellps" || token.key == "datum") {
      if (token.value != "WGS84" && token.value != "GRS80") {
        return std::nullopt;
      }
      if (token.value == "GRS80") {
        tm.f = 1.0 / 298.257222101;
      }
    } else if (token.key == "lat_0" && number) {
      tm.lat0 = *number * kDeg;
    } else if (token.key == "lon_0" && number) {
      tm.lon0 = *number * kDeg;
    } else if ((token.key == "k" || token.key == "k_0") && number) {
      tm.k0 = *number;
    } else if (token.key == "x_0" && number) {
      tm.x0 = *number;
    } else if (token.key == "y_0" && number) {
      tm.y0 = *number;
    } else if (token.key == "zone" && number) {
      zone = static_cast<int>(*number);
    } else if (token.key == "south") {
      south = true;
    } else if (token.key == "units") {
      if (token.value != "m") {
        return std::nullopt;
      }
    } else if (token.key == "towgs84") {
      for (const auto part : split(token.value, ',')) {
        if (parse_double(part).value_or(1.0) != 0.0) {
          return std::nullopt;  // a real datum shift is beyond the simple case
        }
      }
    } else if (token.key != "no_defs" && token.key != "geoidgrids" && token.key != "vunits" &&
               token.key != "type" && token.key != "wktext") {
      return std::nullopt;
    }
  }
  if (kind == "utm") {
    if (!zone || *zone < 1 || *zone > 60) {
      return std::nullopt;
    }
    tm.lat0 = 0.0;
    tm.lon0 = (-183.0 + 6.0 * *zone) * kDeg;
    tm.k0 = 0.9996;
    tm.x0 = 500000.0;
    tm.y0 = south ? 10000000.0 : 0.0;
    return tm;
  }
  if (kind == "tmerc") {
    return tm;
  }
  return std::nullopt;
}

namespace {

// Krüger series coefficients alpha_1..alpha_6 in n (Karney 2011, eq. 35).
void alpha_coefficients(double n, double alpha[6]) {
  const double n2 = n * n, n3 = n2 * n, n4 = n3 * n, n5 = n4 * n, n6 = n5 * n;
  alpha[0] = n / 2 - 2.0 / 3 * n2 + 5.0 / 16 * n3 + 41.0 / 180 * n4 - 127.0 / 288 * n5 +
             7891.0 / 37800 * n6;
  alpha[1] = 13.0 / 48 * n2 - 3.0 / 5 * n3 + 557.0 / 1440 * n4 + 281.0 / 630 * n5 -
             1983433.0 / 1935360 * n6;
  alpha[2] = 61.0 / 240 * n3 - 103.0 / 140 * n4 + 15061.0 / 26880 * n5 + 167603.0 / 181440 * n6;
  alpha[3] = 49561.0 / 161280 * n4 - 179.0 / 168 * n5 + 6601661.0 / 7257600 * n6;
  alpha[4] = 34729.0 / 80640 * n5 - 3418889.0 / 1995840 * n6;
  alpha[5] = 212378941.0 / 319334400 * n6;
}

// Conformal-sphere coordinates (xi, eta) scaled by the rectifying radius A, before k0.
EastNorth krueger(const TransverseMercator& tm, double lat, double dlon) {
  const double n = tm.f / (2.0 - tm.f);
  const double e = std::sqrt(tm.f * (2.0 - tm.f));
  const double big_a =
      tm.a / (1.0 + n) * (1.0 + n * n / 4.0 + std::pow(n, 4) / 64.0 + std::pow(n, 6) / 256.0);
  double alpha[6];
  alpha_coefficients(n, alpha);
  const double sin_lat = std::sin(lat);
  const double t = std::sinh(std::atanh(sin_lat) - e * std::atanh(e * sin_lat));
  const double xi_p = std::atan2(t, std::cos(dlon));
  const double eta_p = std::atanh(std::sin(dlon) / std::sqrt(1.0 + t * t));
  double xi = xi_p;
  double eta = eta_p;
  for (int j = 1; j <= 6; ++j) {
    xi += alpha[j - 1] * std::sin(2 * j * xi_p) * std::cosh(2 * j * eta_p);
    eta += alpha[j - 1] * std::cos(2 * j * xi_p) * std::sinh(2 * j * eta_p);
  }
  return EastNorth{big_a * eta, big_a * xi};
}

}  // namespace

EastNorth project(const TransverseMercator& tm, double lat_deg, double lon_deg) {
  const EastNorth p = krueger(tm, lat_deg * kDeg, lon_deg * kDeg - tm.lon0);
  const EastNorth origin = krueger(tm, tm.lat0, 0.0);
  return EastNorth{tm.x0 + tm.k0 * p.x, tm.y0 + tm.k0 * (p.y - origin.y)};
}

std::optional<EastNorth> geo_to_map(const xodr::Header& header, double lat_deg, double lon_deg) {
  const auto tm = parse_simple_projection(header.geo_reference);
  if (!tm) {
    return std::nullopt;
  }
  const EastNorth geo = project(*tm, lat_deg, lon_deg);
  // OpenDRIVE <offset>: x_geo = offset + R(hdg) x_file, so x_file = R(-hdg) (x_geo - offset).
  const double dx = geo.x - header.offset_x;
  const double dy = geo.y - header.offset_y;
  const double c = std::cos(header.offset_hdg);
  const double s = std::sin(header.offset_hdg);
  return EastNorth{c * dx + s * dy, -s * dx + c * dy};
}

}  // namespace corsa::engine::detail
