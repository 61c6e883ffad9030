#pragma once

// Roadside props generated from a seed (private; plants in vegetation.h): street lights, traffic
// lights, sign posts, guard rails, fences. Each is built in its own frame (x forward = the way it
// faces, z up, the foot at the origin) and placed by the world builder.

#include <string>

#include "corsa/core/random.h"
#include "corsa/sensors/material.h"
#include "mesh_builder.h"
#include "vegetation.h"

namespace corsa::sensors::detail {

/// A street light: a pole `height` metres high with an arm reaching `reach` metres along +x over
/// the road and a lamp head (emissive when it is dark).
ArticulatedMesh make_street_light(double height, double reach);
/// The middle of that street light's lamp head in its frame.
Vec3 street_lamp_head(double height, double reach);

/// How the bulbs of a traffic light are laid out.
enum class SignalLayout { kVertical3, kHorizontal3, kHorizontal4 };
/// A traffic light facing +x: the head's bottom at `bottom` metres, on a post (class pole); the
/// bulbs' materials are switched by the signal's state (red, yellow, green from the top or the
/// left).
ArticulatedMesh make_traffic_light(SignalLayout layout, double bottom, double head_height);

/// A sign facing +x: the face `width` x `height` metres, its bottom `bottom` metres up, on a post.
ArticulatedMesh make_sign(const SignFace& face, double width, double height, double bottom,
                          const std::string& name);

/// The material of a sign's face: `face` drawn over the face's uvs, its fill as base colour.
Material sign_face_material(const SignFace& face, const std::string& name);

/// White road paint, worn (class lane_marking is the caller's): crosswalks, stop lines, outlines.
Material road_paint();

/// A W-beam guard rail `length` metres long along +x (posts every 2 m), or a fence (mesh panels
/// on posts) when `fence`.
ArticulatedMesh make_rail(double length, bool fence);

}  // namespace corsa::sensors::detail
