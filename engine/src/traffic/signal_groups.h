#pragma once

// Signal groups (OpenSCENARIO 1.3 §6.11.2, ASAM OpenDRIVE 1.8 §14.6): a TrafficSignalController's
// `name` is "the reference to an OpenDRIVE signal group ID", the <controller> of the map whose
// <control> entries name the signals that always show the same state. Its phases'
// TrafficSignalGroupState is the observable state of all those signals.

#include <string>
#include <string_view>
#include <vector>

namespace corsa::xodr {
class Map;
}
namespace corsa::xosc {
struct TrafficSignalController;
}

namespace corsa::engine::detail {

/// The signal ids of `controller`'s group: the <control> signals of the map's <controller> whose
/// id is the controller's name (`map` may be null), then the signals its phases name, each once,
/// in that order.
std::vector<std::string> signal_group(const xodr::Map* map,
                                      const xosc::TrafficSignalController& controller);

/// Whether the map (null: none) has a <signal> of id `id` on some road.
bool map_has_signal(const xodr::Map* map, std::string_view id);

/// The signal ids of the map's <controller> of id `id` (empty when there is none).
std::vector<std::string> map_controller_signals(const xodr::Map* map, std::string_view id);

}  // namespace corsa::engine::detail
