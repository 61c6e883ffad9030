#pragma once

// The material a mesh gets when it brings none: the look of its semantic class (private).

#include "corsa/sensors/material.h"
#include "corsa/sensors/semantic.h"

namespace corsa::sensors::detail {

Material default_material(SemanticClass c);

}  // namespace corsa::sensors::detail
