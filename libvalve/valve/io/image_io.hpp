#pragma once
// Reading and writing 3-D images through ITK, keeping spacing, origin and direction:
// NRRD (.nrrd, .nhdr; the default, gzip-compressed), MetaImage (.mha, .mhd), NIfTI (.nii,
// .nii.gz) and DICOM series (a directory; the first series found). ITK types stay inside
// the .cpp.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "valve/imaging/volume.hpp"

namespace valve {

struct ImageHeader {
  ImageGeometry geometry;  // for 2-D images the third size is 1
  int dimension = 3;
  int components = 1;
  std::string pixel_type;  // ITK's component type name ("short", "float", ...)
  int files = 1;           // DICOM: number of slices found
};

/// Reads only the header (for checks before allocating). Throws InputError naming the file
/// for unreadable or unsupported files.
ImageHeader read_image_header(const std::filesystem::path& path);

struct ImageReadOptions {
  /// Refuse volumes whose float copy times `working_copies` exceeds this many bytes
  /// (0: no limit). Checked from the header before any voxel is read.
  double max_bytes = 0;
  int working_copies = 1;
};

/// Reads a scalar 3-D image as float grey values. Refuses 2-D images, multi-component
/// images, DICOM series with missing or unevenly spaced slices, and (with max_bytes) volumes
/// too large for memory, with InputError (file, expected, found).
Volume read_volume(const std::filesystem::path& path, const ImageReadOptions& options = {});
/// Reads a label map (values 0..255).
LabelMap read_label_map(const std::filesystem::path& path);

enum class StoredPixel { int16, float32 };
/// Writes a volume atomically, rounding to int16 by default (smaller, compresses better).
void write_volume(const std::filesystem::path& path, const Volume& volume, StoredPixel pixel = StoredPixel::int16);
void write_label_map(const std::filesystem::path& path, const LabelMap& labels);

/// One label of a label map as 3D Slicer shows it: a named, coloured segment.
struct SegmentDescription {
  std::uint8_t label = 0;
  std::string name;
  Vec3 color = Vec3(0.5, 0.5, 0.5);  // RGB in [0, 1]
};
/// Writes a label map as a 3D Slicer segmentation (.seg.nrrd): the labels as one layer, and
/// the header keys Slicer's segmentation storage reads (Segmentation_* and, per segment,
/// SegmentN_ID, _Name, _Color, _LabelValue, _Layer, _Extent, ...), so that Slicer opens it
/// with the segments named and coloured. A segment without voxels gets an empty extent.
void write_slicer_segmentation(const std::filesystem::path& path, const LabelMap& labels,
                               const std::vector<SegmentDescription>& segments);
/// Writes a DICOM CT series (int16, one file per slice, IM0000.dcm ...) into `directory`.
void write_dicom_series(const std::filesystem::path& directory, const Volume& volume);

/// Smooths with a Gaussian of standard deviation sigma (mm) in every direction
/// (ITK's recursive Gaussian).
void gaussian_blur(Volume& volume, double sigma_mm);

}  // namespace valve
