// ITK headers come first: ITK bundles an older Eigen (itkeigen) under the same include
// guards, and its Geometry module only compiles when its own Core was included first.
#include <itkGDCMImageIO.h>
#include <itkGDCMImageIOFactory.h>
#include <itkGDCMSeriesFileNames.h>
#include <itkImage.h>
#include <itkImageFileReader.h>
#include <itkImageFileWriter.h>
#include <gdcmTrace.h>
#include <itkImageIOFactory.h>
#include <itkImageSeriesReader.h>
#include <itkImportImageFilter.h>
#include <itkMetaDataObject.h>
#include <itkMetaImageIOFactory.h>
#include <itkNiftiImageIOFactory.h>
#include <itkNrrdImageIOFactory.h>
#include <itkSmoothingRecursiveGaussianImageFilter.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <sstream>

#include "valve/core/atomic_file.hpp"
#include "valve/io/image_io.hpp"
#include "valve/core/error.hpp"
#include "valve/imaging/itk_image.hpp"

namespace valve {
namespace fs = std::filesystem;

namespace {

void register_image_io() {
  static std::once_flag once;
  std::call_once(once, [] {
    itk::NrrdImageIOFactory::RegisterOneFactory();
    itk::MetaImageIOFactory::RegisterOneFactory();
    itk::NiftiImageIOFactory::RegisterOneFactory();
    itk::GDCMImageIOFactory::RegisterOneFactory();
    // GDCM prints multi-line warnings on stderr for tags it fills in itself (photometric
    // interpretation, media storage); the stage contract is one line on failure and
    // nothing on success, and real problems still reach us as ITK exceptions.
    gdcm::Trace::WarningOff();
    // ITK warns on stderr about unevenly spaced DICOM slices; read_itk turns that into the
    // stage's one-line error instead.
    itk::Object::GlobalWarningDisplayOff();
  });
}

std::string lower_extension(const fs::path& path) {
  std::string name = path.filename().string();
  std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::tolower(c); });
  if (name.size() > 7 && name.compare(name.size() - 7, 7, ".nii.gz") == 0) return ".nii.gz";
  const auto dot = name.rfind('.');
  return dot == std::string::npos ? "" : name.substr(dot);
}

// Single-file formats only: a header + data pair (.nhdr, .mhd) would be written under the
// temporary name and only the header renamed.
bool is_writable_extension(const std::string& ext) {
  return ext == ".nrrd" || ext == ".mha" || ext == ".nii" || ext == ".nii.gz";
}

// A DICOM directory's slice files, first series, sorted by position.
std::vector<std::string> dicom_files(const fs::path& dir) {
  auto names = itk::GDCMSeriesFileNames::New();
  names->SetUseSeriesDetails(false);  // group by Series Instance UID alone
  names->SetDirectory(dir.string());
  const auto& series = names->GetSeriesUIDs();
  if (series.empty()) throw_input_error(dir.string(), "", "a DICOM series", "a directory without DICOM images");
  return names->GetFileNames(series.front());
}

ImageGeometry geometry_of(const itk::ImageIOBase& io) {
  ImageGeometry g;
  const unsigned dims = io.GetNumberOfDimensions();
  for (unsigned a = 0; a < 3; ++a) {
    g.size[a] = a < dims ? static_cast<int>(io.GetDimensions(a)) : 1;
    g.spacing[a] = a < dims ? io.GetSpacing(a) : 1.0;
    g.origin[a] = a < dims ? io.GetOrigin(a) : 0.0;
    for (unsigned b = 0; b < 3; ++b)
      g.direction(b, a) = (a < dims && b < dims) ? io.GetDirection(a)[b] : (a == b ? 1.0 : 0.0);
  }
  return g;
}

void check_readable(const fs::path& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw_input_error(path.string(), "", "an image file or DICOM directory", "nothing there");
}

template <class Image>
typename Image::Pointer read_itk(const fs::path& path) {
  register_image_io();
  check_readable(path);
  try {
    if (fs::is_directory(path)) {
      const auto files = dicom_files(path);
      auto reader = itk::ImageSeriesReader<Image>::New();
      auto dicom = itk::GDCMImageIO::New();
      reader->SetImageIO(dicom);
      reader->SetFileNames(files);
      reader->Update();
      typename Image::Pointer image = reader->GetOutput();
      double deviation = 0;
      if (itk::ExposeMetaData<double>(image->GetMetaDataDictionary(), "ITK_non_uniform_sampling_deviation", deviation) &&
          deviation > 1e-3 * image->GetSpacing()[2]) {
        std::ostringstream found;
        found << "slice spacing varying by up to " << deviation << " mm across " << files.size() << " slices (missing slices?)";
        throw_input_error(path.string(), "", "evenly spaced slices", found.str());
      }
      return image;
    }
    auto reader = itk::ImageFileReader<Image>::New();
    reader->SetFileName(path.string());
    reader->Update();
    return reader->GetOutput();
  } catch (const itk::ExceptionObject& e) {
    throw_input_error(path.string(), "", "a readable 3-D image", std::string("ITK: ") + e.GetDescription());
  }
}

}  // namespace

ImageHeader read_image_header(const fs::path& path) {
  register_image_io();
  check_readable(path);
  ImageHeader h;
  try {
    std::string file = path.string();
    if (fs::is_directory(path)) {
      const auto files = dicom_files(path);
      h.files = static_cast<int>(files.size());
      file = files.front();
    }
    auto io = itk::ImageIOFactory::CreateImageIO(file.c_str(), itk::ImageIOFactory::FileModeEnum::ReadMode);
    if (!io) throw_input_error(path.string(), "", "an image ITK can read (.nrrd .mha .nii DICOM)", "an unknown format");
    io->SetFileName(file);
    io->ReadImageInformation();
    h.geometry = geometry_of(*io);
    h.dimension = static_cast<int>(io->GetNumberOfDimensions());
    h.components = static_cast<int>(io->GetNumberOfComponents());
    h.pixel_type = itk::ImageIOBase::GetComponentTypeAsString(io->GetComponentType());
    if (fs::is_directory(path)) {
      h.dimension = h.files > 1 ? 3 : h.dimension;
      h.geometry.size[2] = h.files;
    }
  } catch (const itk::ExceptionObject& e) {
    throw_input_error(path.string(), "", "a readable image", std::string("ITK: ") + e.GetDescription());
  }
  return h;
}

Volume read_volume(const fs::path& path, const ImageReadOptions& options) {
  const ImageHeader h = read_image_header(path);
  if (h.dimension != 3 || h.geometry.size[2] < 2) {
    std::ostringstream found;
    found << "a " << h.dimension << "-D image of " << h.geometry.size[0] << " x " << h.geometry.size[1]
          << (h.dimension >= 3 ? " x " + std::to_string(h.geometry.size[2]) : std::string()) << " voxels";
    throw_input_error(path.string(), "", "a 3-D volume", found.str());
  }
  if (h.components != 1)
    throw_input_error(path.string(), "", "a scalar image", std::to_string(h.components) + " components per voxel");
  const double bytes = double(h.geometry.voxel_count()) * sizeof(float) * std::max(1, options.working_copies);
  if (options.max_bytes > 0 && bytes > options.max_bytes) {
    char found[160];
    std::snprintf(found, sizeof found, "%d x %d x %d voxels needing %.1f GB", h.geometry.size[0], h.geometry.size[1],
                  h.geometry.size[2], bytes / 1e9);
    char expected[96];
    std::snprintf(expected, sizeof expected, "a volume that fits in %.1f GB (--max-memory)", options.max_bytes / 1e9);
    throw_input_error(path.string(), "", expected, found);
  }
  auto image = read_itk<itk::Image<float, 3>>(path);
  return volume_from_itk(*image);
}

LabelMap read_label_map(const fs::path& path) {
  const ImageHeader h = read_image_header(path);
  if (h.dimension != 3) throw_input_error(path.string(), "", "a 3-D label map", std::to_string(h.dimension) + "-D image");
  auto image = read_itk<itk::Image<std::uint8_t, 3>>(path);
  return label_map_from_itk(*image);
}

namespace {
template <class Image>
void write_itk(const fs::path& path, Image* image) {
  register_image_io();
  const std::string ext = lower_extension(path);
  if (!is_writable_extension(ext))
    throw_input_error(path.string(), "", "an image file name ending in .nrrd .mha .nii .nii.gz", "\"" + ext + "\"");
  // write_via_temp's temporary keeps the extension ITK picks the format by, is unique across
  // hosts, and joins the files a failed stage removes (labels.nrrd when labels.seg.nrrd fails).
  write_via_temp(path, [&](const fs::path& tmp) {
    try {
      auto writer = itk::ImageFileWriter<Image>::New();
      writer->SetFileName(tmp.string());
      writer->SetInput(image);
      writer->SetUseCompression(true);
      writer->Update();
    } catch (const itk::ExceptionObject& e) {
      throw Error(path.string() + ": cannot write image: " + e.GetDescription());
    }
  });
}
}  // namespace

void write_volume(const fs::path& path, const Volume& volume, StoredPixel pixel) {
  if (pixel == StoredPixel::float32) {
    auto image = volume_to_itk<float>(volume);
    write_itk(path, image.GetPointer());
  } else {
    auto image = volume_to_itk<short>(volume);
    write_itk(path, image.GetPointer());
  }
}

void write_label_map(const fs::path& path, const LabelMap& labels) {
  auto image = label_map_to_itk(labels);
  write_itk(path, image.GetPointer());
}

void write_slicer_segmentation(const fs::path& path, const LabelMap& labels, const std::vector<SegmentDescription>& segments) {
  auto image = label_map_to_itk(labels);
  itk::MetaDataDictionary& dict = image->GetMetaDataDictionary();
  auto put = [&](const std::string& key, const std::string& value) { itk::EncapsulateMetaData<std::string>(dict, key, value); };
  // Slicer's storage node reads these; the labels are one layer in the file's own voxel grid,
  // so the reference extent offset is zero and extents are in file voxel indices.
  put("Segmentation_MasterRepresentation", "Binary labelmap");
  put("Segmentation_ContainedRepresentationNames", "Binary labelmap|");
  put("Segmentation_ReferenceImageExtentOffset", "0 0 0");
  put("Segmentation_ConversionParameters", "");
  const auto& size = labels.geometry.size;
  for (std::size_t s = 0; s < segments.size(); ++s) {
    const SegmentDescription& d = segments[s];
    int lo[3] = {size[0], size[1], size[2]}, hi[3] = {-1, -1, -1};
    for (int k = 0; k < size[2]; ++k)
      for (int j = 0; j < size[1]; ++j)
        for (int i = 0; i < size[0]; ++i)
          if (labels.labels[labels.geometry.linear_index(i, j, k)] == d.label) {
            const int ijk[3] = {i, j, k};
            for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], ijk[a]), hi[a] = std::max(hi[a], ijk[a]);
          }
    std::ostringstream extent, color;
    if (hi[0] < 0) extent << "0 -1 0 -1 0 -1";
    else extent << lo[0] << " " << hi[0] << " " << lo[1] << " " << hi[1] << " " << lo[2] << " " << hi[2];
    color << d.color.x() << " " << d.color.y() << " " << d.color.z();
    const std::string key = "Segment" + std::to_string(s) + "_";
    put(key + "ID", "Segment_" + std::to_string(d.label));
    put(key + "Name", d.name);
    put(key + "NameAutoGenerated", "0");
    put(key + "Color", color.str());
    put(key + "ColorAutoGenerated", "0");
    put(key + "LabelValue", std::to_string(d.label));
    put(key + "Layer", "0");
    put(key + "Extent", extent.str());
    put(key + "Tags", "");
  }
  write_itk(path, image.GetPointer());
}

void write_dicom_series(const fs::path& directory, const Volume& volume) {
  register_image_io();
  // Each slice a 3-D image one voxel deep: GDCM writes position, orientation and pixel
  // spacing from the image geometry (a 2-D slice would carry none of the volume's).
  using Slice = itk::Image<short, 3>;
  const ImageGeometry& g = volume.geometry;
  // A new folder beside the target that no other process or host writing there can take.
  if (directory.has_parent_path()) fs::create_directories(directory.parent_path());
  std::string pattern = (directory.parent_path() / ("." + directory.filename().string() + ".tmpXXXXXX")).string();
  if (!::mkdtemp(pattern.data())) throw Error(directory.string() + ": cannot create a temporary folder beside it");
  const fs::path tmp = pattern;
  fs::permissions(tmp, static_cast<fs::perms>(0777 & ~file_creation_mask()));
  std::error_code ec;
  // UIDs unique per written series (two phantoms must not look like one series to a viewer).
  const auto stamp = std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch()).count();
  const std::string root = "1.2.826.0.1.3680043.9.7433." + std::to_string(stamp) + ".";
  try {
    for (int k = 0; k < g.size[2]; ++k) {
      auto slice = Slice::New();
      Slice::SizeType size{{static_cast<itk::SizeValueType>(g.size[0]), static_cast<itk::SizeValueType>(g.size[1]), 1}};
      slice->SetRegions(Slice::RegionType(size));
      slice->Allocate();
      const Vec3 corner = g.physical_point(Vec3(0, 0, k));
      Slice::PointType origin;
      Slice::SpacingType spacing_xyz;
      Slice::DirectionType direction;
      for (int a = 0; a < 3; ++a) {
        origin[a] = corner[a];
        spacing_xyz[a] = g.spacing[a];
        for (int b = 0; b < 3; ++b) direction(a, b) = g.direction(a, b);
      }
      slice->SetOrigin(origin);
      slice->SetSpacing(spacing_xyz);
      slice->SetDirection(direction);
      for (int j = 0; j < g.size[1]; ++j)
        for (int i = 0; i < g.size[0]; ++i)
          slice->SetPixel({{i, j, 0}}, static_cast<short>(std::lround(std::clamp(volume.values[g.linear_index(i, j, k)], -32768.0f, 32767.0f))));
      auto io = itk::GDCMImageIO::New();
      io->KeepOriginalUIDOn();
      auto& dict = slice->GetMetaDataDictionary();  // the writer hands the image's dictionary to GDCM
      itk::EncapsulateMetaData<std::string>(dict, "0008|0060", "CT");
      itk::EncapsulateMetaData<std::string>(dict, "0008|0016", "1.2.840.10008.5.1.4.1.1.2");
      itk::EncapsulateMetaData<std::string>(dict, "0008|0018", root + "3." + std::to_string(k + 1));
      itk::EncapsulateMetaData<std::string>(dict, "0020|000d", root + "1");
      itk::EncapsulateMetaData<std::string>(dict, "0020|000e", root + "2");
      itk::EncapsulateMetaData<std::string>(dict, "0020|0052", root + "4");  // one frame of reference
      itk::EncapsulateMetaData<std::string>(dict, "0020|0013", std::to_string(k + 1));
      itk::EncapsulateMetaData<std::string>(dict, "0018|0050", std::to_string(g.spacing.z()));
      auto writer = itk::ImageFileWriter<Slice>::New();
      char name[32];
      std::snprintf(name, sizeof name, "IM%04d.dcm", k);
      writer->SetFileName((tmp / name).string());
      writer->SetInput(slice);
      writer->SetImageIO(io);
      writer->Update();
    }
  } catch (const itk::ExceptionObject& e) {
    fs::remove_all(tmp, ec);
    throw Error(directory.string() + ": cannot write DICOM series: " + e.GetDescription());
  }
  fs::remove_all(directory, ec);
  fs::rename(tmp, directory);
}

void gaussian_blur(Volume& volume, double sigma_mm) {
  if (!(sigma_mm >= 0)) throw InputError("gaussian_blur: expected sigma >= 0 mm");
  if (sigma_mm == 0) return;
  auto image = volume_to_itk<float>(volume);
  auto blur = itk::SmoothingRecursiveGaussianImageFilter<itk::Image<float, 3>>::New();
  blur->SetInput(image);
  blur->SetSigma(sigma_mm);
  blur->Update();
  volume = volume_from_itk(*blur->GetOutput());
}

}  // namespace valve
