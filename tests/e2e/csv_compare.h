#pragma once

// Reading trajectory CSVs (time,entity,x,y,z,h,p,r,speed,road,lane,s,t) as numbers, and
// comparing a run with its golden within tolerances.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "corsa/core/strings.h"

namespace corsa::test {

struct TrajectoryRow {
  double time = 0.0;
  std::string entity;
  double x = 0, y = 0, z = 0, h = 0, p = 0, r = 0, speed = 0;
  std::string road;  ///< empty off the road
  int lane = 0;
  double s = 0.0, t = 0.0;
};

inline std::vector<TrajectoryRow> parse_trajectory(const std::string& text) {
  std::vector<TrajectoryRow> rows;
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  REQUIRE(line == "time,entity,x,y,z,h,p,r,speed,road,lane,s,t");
  while (std::getline(in, line)) {
    const auto f = split(line, ',');
    REQUIRE(f.size() == 13);
    TrajectoryRow row;
    const auto number = [&](size_t i) {
      const auto value = parse_double(f[i]);
      REQUIRE(value);
      return *value;
    };
    row.time = number(0);
    row.entity = std::string(f[1]);
    row.x = number(2);
    row.y = number(3);
    row.z = number(4);
    row.h = number(5);
    row.p = number(6);
    row.r = number(7);
    row.speed = number(8);
    row.road = std::string(f[9]);
    if (!row.road.empty()) {
      row.lane = static_cast<int>(*parse_int(f[10]));
      row.s = number(11);
      row.t = number(12);
    }
    rows.push_back(row);
  }
  return rows;
}

/// Positions within 1 mm, angles within 1e-6 rad, speeds within 1e-6 m/s; the same entities,
/// roads and lanes at the same times.
inline void check_against_golden(const std::vector<TrajectoryRow>& run,
                                 const std::vector<TrajectoryRow>& golden) {
  REQUIRE(run.size() == golden.size());
  size_t mismatches = 0;
  for (size_t i = 0; i < run.size(); ++i) {
    const TrajectoryRow& a = run[i];
    const TrajectoryRow& b = golden[i];
    const bool same = a.time == b.time && a.entity == b.entity && a.road == b.road &&
                      a.lane == b.lane && std::abs(a.x - b.x) <= 1e-3 &&
                      std::abs(a.y - b.y) <= 1e-3 && std::abs(a.z - b.z) <= 1e-3 &&
                      std::abs(std::remainder(a.h - b.h, 2.0 * 3.141592653589793)) <= 1e-6 &&
                      std::abs(a.speed - b.speed) <= 1e-6 && std::abs(a.s - b.s) <= 1e-3 &&
                      std::abs(a.t - b.t) <= 1e-3;
    if (!same && ++mismatches <= 5) {
      INFO("row " << i + 2 << ": " << a.time << " " << a.entity << " at (" << a.x << ", " << a.y
                  << ") speed " << a.speed << " lane " << a.road << "/" << a.lane
                  << "; golden: " << b.time << " " << b.entity << " at (" << b.x << ", " << b.y
                  << ") speed " << b.speed << " lane " << b.road << "/" << b.lane);
      CHECK(same);
    }
  }
  CHECK(mismatches == 0);
}

/// The rows of one entity, in time order.
inline std::vector<TrajectoryRow> of(const std::vector<TrajectoryRow>& rows,
                                     const std::string& entity) {
  std::vector<TrajectoryRow> out;
  for (const auto& row : rows) {
    if (row.entity == entity) {
      out.push_back(row);
    }
  }
  return out;
}

/// The row of `entity` at `time` (within 1e-9 s); a failed requirement when there is none.
inline const TrajectoryRow& row_at(const std::vector<TrajectoryRow>& rows,
                                   const std::string& entity, double time) {
  const auto it = std::find_if(rows.begin(), rows.end(), [&](const TrajectoryRow& row) {
    return row.entity == entity && std::abs(row.time - time) < 1e-9;
  });
  REQUIRE(it != rows.end());
  return *it;
}

}  // namespace corsa::test
