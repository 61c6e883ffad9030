#pragma once

// Internal: whether a folder may receive a dataset, and the replacing of a previous one
// (dataset_writer.h). Only the files of the previous dataset are ever removed, never a file
// Corsa did not write.

#include <filesystem>

namespace corsa::sensors::detail {

/// Prepares `dir`, which exists and is locked by the caller, for a new dataset. It must be
/// empty (but for the lock and Corsa's temporaries), or, with `replace`, hold a previous dataset
/// and nothing else: then that dataset's files are removed, and the folders it made when they
/// are left empty. A previous dataset's files are those its run.json and frames.csv name: both,
/// every file frames.csv lists, and for each sensor in run.json its calibration.json and its
/// frame files (a killed run may have written a capture it did not index yet); the pose files;
/// the KITTI export's frame files; the preview. Anything else in the folder (a file the user put
/// there) makes it an InputError naming a few of them, before anything is removed.
void prepare_dataset_folder(const std::filesystem::path& dir, bool replace);

}  // namespace corsa::sensors::detail
