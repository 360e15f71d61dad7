#pragma once
// What a segmentation costs in memory and what valve-segment reports of it.
#include <string>

#include <nlohmann/json.hpp>

#include "valve/imaging/segmentation.hpp"

namespace valve {

/// How many float copies of the input image segment_valve holds at once, for the reader's
/// memory check: the input, its smoothed copy, masks and 32-bit component labels (6); the
/// Hessian method adds a six-float tensor, a three-float gradient and its filters'
/// intermediate float images (18 in all).
int segmentation_working_copies(const SegmentationOptions& options);

/// The summary's metrics: the files NAME.nrrd and NAME.seg.nrrd, the threshold, the cropped
/// grid, voxel counts and their volumes (count × voxel volume), components and chordae.
nlohmann::json segmentation_metrics(const SegmentationSummary& summary, const SegmentationOptions& options,
                                    const std::string& name);

}  // namespace valve
