#pragma once

// Facades in real geometry (private to the library): one building's style drawn from its seed
// (storey heights, bays, window sizes and frames, recess depth, ledges, cornice, parapet,
// pilasters, balconies, shop fronts) and the walls it dresses, each a rectangle cut into piers
// and recessed openings with reveals, sills and panes. Every part is class `building`; the
// panes are the glazing pattern (frames, curtains, rooms lit at night, per window), the walls
// the plaster pattern (no painted windows).

#include <cstdint>

#include "corsa/core/random.h"
#include "corsa/sensors/static_mesh.h"
#include "mesh_builder.h"

namespace corsa::sensors::detail {

/// One building's facade style: sizes in metres, drawn once per building (draw_facade_style).
struct FacadeStyle {
  double floor_h = 3.0;   ///< storey height
  double ground_h = 3.0;  ///< ground-floor height (taller with shop fronts)
  bool shops = false;     ///< shop fronts on the ground floor of street walls
  double bay = 3.0;       ///< window spacing along the wall (rounded to fit each wall)
  double window_w = 1.3;
  double window_h = 1.6;
  double sill_z = 0.9;              ///< window bottom above the storey's floor
  double top_window_scale = 1.0;    ///< top-floor window height factor (attic windows)
  double first_window_scale = 1.0;  ///< first-floor window height factor (taller, piano nobile)
  double recess = 0.2;              ///< depth of the window reveals
  bool ledges = false;              ///< a string course at every floor line
  bool pilasters = false;           ///< pilasters between bays above the ground floor
  double balconies = 0.0;           ///< share of upper bays with a balcony (0 none)
  double cornice = 0.0;             ///< cornice height at the top (0 none)
  double parapet = 0.0;             ///< parapet height above the roof (0 none)
  Material plaster;                 ///< walls above the ground floor
  Material base;                    ///< the ground floor's walls (a plinth or shop-front stone)
  Material trim;                    ///< sills, ledges, cornice, coping, balcony slabs
  Material railing;
  Material glazing;       ///< upper windows (pattern kGlazing)
  Material top_glazing;   ///< top-floor windows
  Material shop_glazing;  ///< shop windows
  Material door;          ///< entrance doors
  Material fascia[3];     ///< shop sign bands
  Material awning;
};

/// What a building is, for drawing its style.
struct FacadeBrief {
  Color wall;             ///< linear wall colour
  double floor_h = 3.0;   ///< storey height; 0 draws one
  double ground_h = 0.0;  ///< ground-floor height with shop fronts; 0 none, < 0 draws
  bool flat_roof = true;  ///< cornice and parapet only on flat roofs
  uint32_t seed = 0;      ///< varies the patterns
};

FacadeStyle draw_facade_style(RandomStream& rng, const FacadeBrief& brief);

/// A rectangular wall in a builder's frame: its base from `a` to `b` (the outside on the right
/// of a -> b seen from above), `height` metres up.
struct FacadeWall {
  Vec3 a;
  Vec3 b;
  double height = 0.0;
  bool street = true;  ///< shop fronts and doors (else windows only)
};

/// Adds one wall with its openings, reveals, sills, ledges, cornice and parapet; `rng` draws
/// the per-bay choices (balconies, doors, sign colours).
void add_facade_wall(MeshBuilder& b, const FacadeWall& wall, const FacadeStyle& style,
                     RandomStream& rng);

/// A building mesh that brings only a colour (a model's or an extruded footprint's), dressed:
/// each vertical rectangle of its walls (3 m wide and 2.5 m high or more) becomes a facade
/// drawn from `seed`, the rest (roofs, other walls) keeps `rest`. The mesh keeps its class,
/// instance id and name; it gets a material palette.
StaticMesh dress_building(StaticMesh mesh, const Material& rest, uint64_t seed);

}  // namespace corsa::sensors::detail
