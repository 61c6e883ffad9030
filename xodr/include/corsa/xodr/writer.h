#pragma once

// MapData -> OpenDRIVE 1.8 text. Numbers are written as the shortest decimal text that reads back
// to exactly the same double, so write -> parse gives back identical MapData (lines aside).
// Output is deterministic: same MapData, same bytes.

#include <filesystem>
#include <string>

#include "corsa/xodr/model.h"

namespace corsa::xodr {

struct WriteOptions {
  /// <header revMinor>: the writer emits 1.8 structure; older minors only change the number.
  int rev_minor = 8;
  /// At most one <predecessor> and one <successor> per lane link (what readers of OpenDRIVE
  /// 1.4 follow); the others are left out.
  bool single_lane_links = false;
  /// Direct junctions (§10.5, OpenDRIVE 1.7) written in the form earlier readers follow: a
  /// junction without a type whose connections name the linked road as connectingRoad (readers
  /// such as libOpenDRIVE skip connections without one).
  bool legacy_junctions = false;
};

/// Options for files that readers of OpenDRIVE 1.4 follow (`corsa convert ngii --compat 1.4`):
/// revMinor 4, legacy junctions, one lane predecessor/successor.
WriteOptions compat_options(int rev_minor);

/// The whole document as text.
std::string write_xodr_text(const MapData& map, const WriteOptions& options = {});

/// Writes the document to `path` atomically (a temporary file renamed into place), so a failure
/// never leaves a half-written map. Throws corsa::InputError on I/O failure.
void write_xodr(const MapData& map, const std::filesystem::path& path,
                const WriteOptions& options = {});

}  // namespace corsa::xodr
