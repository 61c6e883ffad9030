#pragma once

// Surface materials of the scene: a base colour (linear RGB) or a texture (a procedural pattern
// with its parameters, or an image read from a user's file), metallic/roughness, a clear-coat
// layer, transmission with an index of refraction (glass), and emission switched by a light
// role (vehicle lamps by the entity's light state, traffic-light bulbs by the signal state,
// street lamps by darkness). Meshes carry a palette of materials and one index per triangle;
// the scene merges the palettes into one table.

#include <array>
#include <cstdint>
#include <memory>
#include <string>

#include "corsa/sensors/color.h"

namespace corsa::sensors {

class TextureImage;

/// Index into a scene's material table.
using MaterialId = uint16_t;

/// Procedural patterns: deterministic functions of the surface position (metres) and the
/// material's seed, prefiltered to the pixel footprint (mip-mapped noise and box-filtered line
/// patterns) so that they do not alias. `Material::params` means, per pattern:
enum class Pattern : uint8_t {
  kNone,
  kAsphalt,    ///< aggregate grain, wear and repair patches, cracks; params[0] wear 0..1
  kConcrete,   ///< cement slabs with joints every pattern_scale metres (sidewalks, kerbs)
  kPaving,     ///< paving bricks pattern_scale long, half as wide, running bond
  kFacade,     ///< walls: floors pattern_scale high; params {bay width m, window width share,
               ///< window height share, ground floor height m}; secondary = frames and trim
  kRoof,       ///< flat roofs: gravel and tar patches
  kFoliage,    ///< leaf clusters in two greens (secondary the darker one)
  kGrass,      ///< lawn with dry patches
  kDirt,       ///< bare soil and gravel
  kTerrain,    ///< grass and dirt mixed at the scale of tens of metres
  kBark,       ///< vertical bark furrows
  kRubber,     ///< tyre rubber, lettering-free sidewall
  kSignFace,   ///< a traffic-sign face drawn from the mesh's uv and Material::sign
  kPlate,      ///< licence plate: characters in secondary on the base colour, from uv
  kMetalGrid,  ///< louvres and grilles: dark slots across a metal part
  kPaint,      ///< road paint worn down to the asphalt (secondary) in patches
  kPlaster,    ///< walls without painted windows (the facade generator's are geometry), and
               ///< their window reveals
  kGlazing,    ///< window panes from uv (u: column + share across, v: floor + share up);
               ///< params {pane width m, pane height m, mullions, transom share from the top};
               ///< base_color the room behind, secondary the frame
};

/// What switches a material's emission on.
enum class LightRole : uint8_t {
  kNone,           ///< no emission
  kAlways,         ///< always emitting (displays)
  kHeadlight,      ///< vehicle low beam (at night, or when the light state says so)
  kTail,           ///< rear position lamps (with the headlights)
  kBrake,          ///< brake lamps
  kIndicatorLeft,  ///< flashing direction indicators (and the warning lights)
  kIndicatorRight,
  kReversing,
  kStreetLamp,  ///< on when it is dark
  kSignalRed,   ///< traffic-light bulbs, by the signal's state
  kSignalYellow,
  kSignalGreen,
};

/// Shapes of traffic-sign faces (the face fills the uv square [0, 1]^2, v up).
enum class SignShape : uint8_t {
  kCircle,
  kTriangleUp,    ///< warning signs
  kTriangleDown,  ///< give way
  kOctagon,       ///< stop
  kSquare,
  kDiamond,  ///< priority road
  kRectangle,
};

/// The symbol drawn on a sign face.
enum class SignSymbol : uint8_t {
  kNone,
  kNumber,    ///< SignFace::number (speed limits), in a seven-segment style
  kBar,       ///< a horizontal bar (no entry)
  kStopText,  ///< "STOP"
  kArrowUp,   ///< mandatory direction
  kArrowLeft,
  kArrowRight,
  kExclamation,   ///< general danger
  kPerson,        ///< pedestrian crossing
  kDiagonal,      ///< end of restriction
  kInnerDiamond,  ///< the yellow square of a priority road sign
  kCross,         ///< no stopping, crossroads
};

struct SignFace {
  SignShape shape = SignShape::kCircle;
  Color fill{0.9, 0.9, 0.9};
  Color border{0.6, 0.02, 0.02};
  double border_width = 0.15;  ///< share of the face's half size
  SignSymbol symbol = SignSymbol::kNone;
  Color symbol_color{0.01, 0.01, 0.01};
  int number = 0;
  double aspect = 1.0;  ///< width / height of the face (plates are 4.7), so glyphs keep shape
};

struct Material {
  std::string name;                 ///< for messages and files
  Color base_color{0.2, 0.2, 0.2};  ///< linear albedo; multiplies the texture
  Pattern pattern = Pattern::kNone;
  uint32_t seed = 0;           ///< varies the pattern (no two buildings alike)
  double pattern_scale = 1.0;  ///< metres: the pattern's feature size
  std::array<double, 4> params{};
  Color secondary{0.05, 0.05, 0.05};  ///< the pattern's second colour
  SignFace sign;                      ///< Pattern::kSignFace only
  /// A picture (from a model file) read at the mesh's texture coordinates; multiplies
  /// base_color. Null: none.
  std::shared_ptr<const TextureImage> image;
  double metallic = 0.0;      ///< 0 dielectric .. 1 metal
  double roughness = 0.8;     ///< 0 mirror .. 1 matte (perceptual, as in glTF)
  double clearcoat = 0.0;     ///< 0..1 weight of a clear lacquer layer (car paint)
  double transmission = 0.0;  ///< 0 opaque .. 1 clear (glass)
  double ior = 1.5;           ///< index of refraction (glass 1.5, water 1.33)
  Color emission;             ///< linear radiance when switched on
  LightRole light = LightRole::kNone;
};

/// A few ready-made materials in linear colour (the shared look of generated content).
namespace materials {
Material plain(std::string name, Color base, double roughness = 0.8);
Material glass(std::string name = "glass");
Material metal(std::string name, Color base, double roughness = 0.35);
Material lamp(std::string name, Color lens, Color emission, LightRole role);
}  // namespace materials

}  // namespace corsa::sensors
