#pragma once

// The state of one 4x4 tile of a camera pass between its primary rays (camera_trace.cpp) and
// its secondary rays (camera_rays.cpp): the surface each pixel shows and what its sun, sky,
// lamp, mirror and glass rays found.

#include "camera_frame.h"

namespace corsa::sensors::detail {

struct TileState {
  int count = 0;
  size_t pixel[16] = {};
  bool hit[16] = {};
  Vec3 dir[16];
  SurfacePoint surface[16];
  Visibility vis[16];
  Color mirrored[16], behind[16];
  bool has_mirrored[16] = {}, has_behind[16] = {};
  int sun_rays[16] = {}, sun_free[16] = {};
  int light_rays[16] = {}, light_free[16] = {};
  Color sky_sum[16];
  int sky_rays[16] = {};
};

/// Queues the secondary rays of hit pixel k of the tile (its surface is set).
void queue_rays(const Pass& p, TileState& t, int k, TileScratch& s);

/// Traces the queued rays of a tile and turns them into each hit pixel's visibilities and the
/// radiance its mirror and glass rays bring back.
void resolve_rays(const Pass& p, TileState& t, TileScratch& s);

}  // namespace corsa::sensors::detail
