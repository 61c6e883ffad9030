#pragma once

// The actions of `corsa map`, one file each (map_info.cpp, map_query.cpp, map_render.cpp,
// map_mesh.cpp, map_holes.cpp). Each receives the arguments after the action name.

#include <span>
#include <string>

namespace corsa::cli {

int map_info(std::span<const std::string> args);
int map_query(std::span<const std::string> args);
int map_render(std::span<const std::string> args);
int map_mesh(std::span<const std::string> args);
int map_holes(std::span<const std::string> args);

}  // namespace corsa::cli
