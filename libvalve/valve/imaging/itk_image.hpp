#pragma once
// Conversions between valve's Volume / LabelMap and itk::Image. Include only from the
// ITK translation units of valve_itk (image_io.cpp, segmentation.cpp).
#include <itkImage.h>

#include <algorithm>
#include <cmath>

#include "valve/imaging/volume.hpp"

namespace valve {

template <class Image>
void set_itk_geometry(Image& image, const ImageGeometry& g) {
  typename Image::SizeType size;
  typename Image::SpacingType spacing;
  typename Image::PointType origin;
  typename Image::DirectionType direction;
  for (unsigned a = 0; a < 3; ++a) {
    size[a] = static_cast<itk::SizeValueType>(g.size[a]);
    spacing[a] = g.spacing[a];
    origin[a] = g.origin[a];
    for (unsigned b = 0; b < 3; ++b) direction(b, a) = g.direction(b, a);
  }
  image.SetRegions(typename Image::RegionType(size));
  image.SetSpacing(spacing);
  image.SetOrigin(origin);
  image.SetDirection(direction);
}

template <class Image>
ImageGeometry itk_geometry(const Image& image) {
  ImageGeometry g;
  const auto region = image.GetLargestPossibleRegion();
  for (unsigned a = 0; a < 3; ++a) {
    g.size[a] = static_cast<int>(region.GetSize()[a]);
    g.spacing[a] = image.GetSpacing()[a];
    g.origin[a] = image.GetOrigin()[a];
    for (unsigned b = 0; b < 3; ++b) g.direction(b, a) = image.GetDirection()(b, a);
  }
  // A region that does not start at index 0 (an ROI): move the origin to its first voxel.
  Vec3 start(region.GetIndex()[0], region.GetIndex()[1], region.GetIndex()[2]);
  g.origin = g.physical_point(start);
  return g;
}

/// Copies grey values into a new ITK image of pixel type T (rounded and clamped for integers).
template <class T>
typename itk::Image<T, 3>::Pointer volume_to_itk(const Volume& volume) {
  auto image = itk::Image<T, 3>::New();
  set_itk_geometry(*image, volume.geometry);
  image->Allocate();
  T* out = image->GetBufferPointer();
  for (std::size_t v = 0; v < volume.values.size(); ++v) {
    if constexpr (std::is_floating_point_v<T>) {
      out[v] = static_cast<T>(volume.values[v]);
    } else {
      const double lo = std::numeric_limits<T>::lowest(), hi = std::numeric_limits<T>::max();
      out[v] = static_cast<T>(std::clamp(std::round(double(volume.values[v])), lo, hi));
    }
  }
  return image;
}

template <class Image>
Volume volume_from_itk(const Image& image) {
  Volume v{itk_geometry(image), {}};
  const auto* in = image.GetBufferPointer();
  v.values.assign(in, in + v.geometry.voxel_count());
  return v;
}

inline itk::Image<std::uint8_t, 3>::Pointer label_map_to_itk(const LabelMap& labels) {
  auto image = itk::Image<std::uint8_t, 3>::New();
  set_itk_geometry(*image, labels.geometry);
  image->Allocate();
  std::copy(labels.labels.begin(), labels.labels.end(), image->GetBufferPointer());
  return image;
}

template <class Image>
LabelMap label_map_from_itk(const Image& image) {
  LabelMap m{itk_geometry(image), {}};
  const auto* in = image.GetBufferPointer();
  m.labels.resize(m.geometry.voxel_count());
  for (std::size_t v = 0; v < m.labels.size(); ++v) m.labels[v] = static_cast<std::uint8_t>(in[v]);
  return m;
}

}  // namespace valve
