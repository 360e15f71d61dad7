// ITK headers come first: ITK bundles an older Eigen (itkeigen) under the same include
// guards, and its Geometry module only compiles when its own Core was included first.
#include <itkBinaryBallStructuringElement.h>
#include <itkBinaryDilateImageFilter.h>
#include <itkBinaryMorphologicalClosingImageFilter.h>
#include <itkBinaryMorphologicalOpeningImageFilter.h>
#include <itkBinaryThresholdImageFilter.h>
#include <itkConnectedComponentImageFilter.h>
#include <itkCurvatureAnisotropicDiffusionImageFilter.h>
#include <itkGradientRecursiveGaussianImageFilter.h>
#include <itkHessianRecursiveGaussianImageFilter.h>
#include <itkMedianImageFilter.h>
#include <itkOtsuThresholdImageFilter.h>
#include <itkRegionOfInterestImageFilter.h>
#include <itkRelabelComponentImageFilter.h>
#include <itkSmoothingRecursiveGaussianImageFilter.h>
#include <itkSymmetricSecondRankTensor.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <sstream>

#include "valve/imaging/segmentation.hpp"
#include "valve/core/error.hpp"
#include "valve/imaging/itk_image.hpp"

namespace valve {
namespace {

using FloatImage = itk::Image<float, 3>;
using MaskImage = itk::Image<std::uint8_t, 3>;
using LabelImage = itk::Image<std::uint32_t, 3>;
using Ball = itk::BinaryBallStructuringElement<std::uint8_t, 3>;

// A mask on grid g, all background.
MaskImage::Pointer empty_mask(const ImageGeometry& g) {
  auto mask = MaskImage::New();
  set_itk_geometry(*mask, g);
  mask->Allocate();
  mask->FillBuffer(0);
  return mask;
}

// A ball of physical radius r as voxel radii per axis; false if it is under one voxel on an axis.
bool ball_of(double radius_mm, const ImageGeometry& g, Ball* ball) {
  Ball::SizeType r;
  for (int a = 0; a < 3; ++a) {
    const long n = std::lround(radius_mm / g.spacing[a]);
    if (n < 1) return false;
    r[a] = static_cast<itk::SizeValueType>(n);
  }
  ball->SetRadius(r);
  ball->CreateStructuringElement();
  return true;
}

// A binary closing or opening of the foreground (value 1) with the ball.
template <template <class, class, class> class Filter>
MaskImage::Pointer morphology(MaskImage::Pointer mask, const Ball& ball) {
  auto filter = Filter<MaskImage, MaskImage, Ball>::New();
  filter->SetInput(mask);
  filter->SetKernel(ball);
  filter->SetForegroundValue(1);
  filter->Update();
  return filter->GetOutput();
}

FloatImage::Pointer crop(FloatImage::Pointer image, const SegmentationOptions& o, const ImageGeometry& g) {
  if (!o.crop) return image;
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  for (int c = 0; c < 8; ++c) {
    const Vec3 corner((c & 1) ? o.crop_hi.x() : o.crop_lo.x(), (c & 2) ? o.crop_hi.y() : o.crop_lo.y(),
                      (c & 4) ? o.crop_hi.z() : o.crop_lo.z());
    const Vec3 idx = g.continuous_index(corner);
    lo = lo.cwiseMin(idx);
    hi = hi.cwiseMax(idx);
  }
  FloatImage::IndexType start;
  FloatImage::SizeType size;
  for (int a = 0; a < 3; ++a) {
    const long from = std::max(0L, static_cast<long>(std::ceil(lo[a] - 1e-9)));
    const long to = std::min<long>(g.size[a] - 1, static_cast<long>(std::floor(hi[a] + 1e-9)));
    if (to - from < 1) throw_input_error("segmentation", "crop", "a box overlapping the image by at least 2 voxels per axis",
                                         "an overlap of " + std::to_string(std::max(0L, to - from + 1)) + " voxels on axis " + std::to_string(a));
    start[a] = from;
    size[a] = static_cast<itk::SizeValueType>(to - from + 1);
  }
  auto roi = itk::RegionOfInterestImageFilter<FloatImage, FloatImage>::New();
  roi->SetInput(image);
  roi->SetRegionOfInterest(FloatImage::RegionType(start, size));
  roi->Update();
  return roi->GetOutput();
}

FloatImage::Pointer denoise(FloatImage::Pointer image, const SegmentationOptions& o) {
  if (o.denoise == "gaussian" && o.gaussian_sigma > 0) {
    auto f = itk::SmoothingRecursiveGaussianImageFilter<FloatImage, FloatImage>::New();
    f->SetInput(image);
    f->SetSigma(o.gaussian_sigma);
    f->Update();
    image = f->GetOutput();
  } else if (o.denoise == "median" && o.median_radius > 0) {
    auto f = itk::MedianImageFilter<FloatImage, FloatImage>::New();
    f->SetInput(image);
    FloatImage::SizeType r;
    r.Fill(static_cast<itk::SizeValueType>(o.median_radius));
    f->SetRadius(r);
    f->Update();
    image = f->GetOutput();
  }
  if (o.diffusion_iterations > 0) {
    auto f = itk::CurvatureAnisotropicDiffusionImageFilter<FloatImage, FloatImage>::New();
    f->SetInput(image);
    f->SetNumberOfIterations(static_cast<unsigned>(o.diffusion_iterations));
    f->SetConductanceParameter(o.diffusion_conductance);
    // Stable explicit step for 3-D: 1/2^(N+1) times the smallest spacing.
    f->SetTimeStep(0.0625 * std::min({image->GetSpacing()[0], image->GetSpacing()[1], image->GetSpacing()[2]}));
    f->Update();
    image = f->GetOutput();
  }
  return image;
}

// The tissue voxels lying on bright tubes. Hessian of the image at the given scale,
// eigenvalues ordered by magnitude |l1| <= |l2| <= |l3|: a bright tube curves down across both
// its cross-section axes (l2, l3 < 0 and alike), a bright sheet across its thickness only
// (l2 ~ 0). Voxels with l2/l3 >= tube_ratio lying within tube_ridge_offset of the ridge
// along the second axis (from gradient / l2) seed the tubes, which then grow by up to
// tube_growth_voxels into tissue that is not clearly inside a sheet: l2/l3 >= sheet_ratio, or
// the image does not curve down along every axis (the largest eigenvalue by value >= 0, as on
// a surface or next to noise in a sheet's flat directions; the notch closing below returns
// sheet voxels taken that way). Near a tube's surface the ratio falls: on the Texas TriValve's
// open frame the seeds hold about half the chord voxels; with the growth the stage labels 95 %
// of them chordae and keeps 99 % of the leaflet voxels (counted against the deck's geometry).
MaskImage::Pointer tube_voxels(FloatImage::Pointer image, MaskImage::Pointer tissue, const ImageGeometry& g,
                               const SegmentationOptions& o) {
  using Tensor = itk::SymmetricSecondRankTensor<float, 3>;
  using TensorImage = itk::Image<Tensor, 3>;
  auto hessian = itk::HessianRecursiveGaussianImageFilter<FloatImage, TensorImage>::New();
  hessian->SetInput(image);
  hessian->SetSigma(o.tube_scale);
  hessian->Update();
  const Tensor* h = hessian->GetOutput()->GetBufferPointer();
  using Gradient = itk::CovariantVector<float, 3>;
  auto gradient = itk::GradientRecursiveGaussianImageFilter<FloatImage, itk::Image<Gradient, 3>>::New();
  gradient->SetInput(image);
  gradient->SetSigma(o.tube_scale);
  // In index axes, as the Hessian's eigenvectors are (the filter rotates into physical space
  // by default, which would mix frames on an oblique image).
  gradient->SetUseImageDirection(false);
  gradient->Update();
  const Gradient* grad = gradient->GetOutput()->GetBufferPointer();
  const std::size_t n = g.voxel_count();
  const MaskImage::Pointer tubes = empty_mask(g);
  const std::uint8_t* t = tissue->GetBufferPointer();
  std::uint8_t* tube = tubes->GetBufferPointer();
  std::vector<std::uint8_t> may_grow(n, 0);
  for (std::size_t v = 0; v < n; ++v) {
    if (!t[v]) continue;
    Tensor::EigenValuesArrayType l;
    Tensor::EigenVectorsMatrixType e;
    h[v].ComputeEigenAnalysis(l, e);
    int order[3] = {0, 1, 2};
    std::sort(order, order + 3, [&](int a, int b) { return std::abs(l[a]) < std::abs(l[b]); });
    const double l2 = l[order[1]], l3 = l[order[2]];
    const double ratio = (l3 < 0 && l2 < 0) ? l2 / l3 : 0.0;
    // Distance to the ridge along the second axis, from the local quadratic: a tube's axis is
    // a maximum across both its axes; the rim of a sheet rises into the sheet instead.
    double slope = 0;
    for (int a = 0; a < 3; ++a) slope += grad[v][a] * e(order[1], a);
    const double to_ridge = l2 < 0 ? std::abs(slope / l2) : 1e300;
    tube[v] = ratio >= o.tube_ratio && to_ridge <= o.tube_ridge_offset;
    may_grow[v] = ratio >= o.sheet_ratio || l[2] >= 0;  // ITK orders l by value: l[2] is the largest
  }
  Ball unit;
  Ball::SizeType one;
  one.Fill(1);
  unit.SetRadius(one);
  unit.CreateStructuringElement();
  for (int pass = 0; pass < o.tube_growth_voxels; ++pass) {
    auto dilate = itk::BinaryDilateImageFilter<MaskImage, MaskImage, Ball>::New();
    dilate->SetInput(tubes);
    dilate->SetKernel(unit);
    dilate->SetForegroundValue(1);
    dilate->Update();
    const std::uint8_t* grown = dilate->GetOutput()->GetBufferPointer();
    for (std::size_t v = 0; v < n; ++v) tube[v] = tube[v] || (grown[v] && may_grow[v]);
  }
  return tubes;
}

// Connected components (face-connected), relabelled by decreasing size, pieces under
// min_voxels dropped.
LabelImage::Pointer components(MaskImage::Pointer mask, std::size_t min_voxels, bool full_connectivity) {
  auto cc = itk::ConnectedComponentImageFilter<MaskImage, LabelImage>::New();
  cc->SetInput(mask);
  cc->SetFullyConnected(full_connectivity);
  auto relabel = itk::RelabelComponentImageFilter<LabelImage, LabelImage>::New();
  relabel->SetInput(cc->GetOutput());
  relabel->SetMinimumObjectSize(min_voxels);
  relabel->Update();
  return relabel->GetOutput();
}

std::string format_point(const Vec3& p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.2f, %.2f, %.2f) mm", p.x(), p.y(), p.z());
  return buf;
}

}  // namespace

void SegmentationOptions::validate(const std::string& where) const {
  if (denoise != "none" && denoise != "gaussian" && denoise != "median")
    throw_input_error(where, "denoise", "none|gaussian|median", "\"" + denoise + "\"");
  if (threshold_method != "otsu" && threshold_method != "explicit")
    throw_input_error(where, "threshold", "otsu or a grey value", "\"" + threshold_method + "\"");
  if (!(gaussian_sigma >= 0)) throw_input_error(where, "gaussian_sigma", "a length >= 0 mm", std::to_string(gaussian_sigma));
  if (median_radius < 0 || median_radius > 10) throw_input_error(where, "median_radius", "0..10 voxels", std::to_string(median_radius));
  if (diffusion_iterations < 0 || diffusion_iterations > 1000)
    throw_input_error(where, "diffusion_iterations", "0..1000", std::to_string(diffusion_iterations));
  if (!(closing_radius >= 0)) throw_input_error(where, "closing_radius", "a length >= 0 mm", std::to_string(closing_radius));
  if (chordae_method != "opening" && chordae_method != "hessian")
    throw_input_error(where, "chordae_method", "opening|hessian", "\"" + chordae_method + "\"");
  if (!(tube_scale > 0)) throw_input_error(where, "tube_scale", "a length > 0 mm", std::to_string(tube_scale));
  if (!(tube_ratio > 0 && tube_ratio <= 1)) throw_input_error(where, "tube_ratio", "a ratio in (0, 1]", std::to_string(tube_ratio));
  if (!(tube_ridge_offset >= 0)) throw_input_error(where, "tube_ridge_offset", "a length >= 0 mm", std::to_string(tube_ridge_offset));
  if (!(sheet_ratio >= 0 && sheet_ratio <= tube_ratio))
    throw_input_error(where, "sheet_ratio", "a ratio in [0, tube_ratio]", std::to_string(sheet_ratio));
  if (tube_growth_voxels < 0 || tube_growth_voxels > 10)
    throw_input_error(where, "tube_growth_voxels", "0..10", std::to_string(tube_growth_voxels));
  if (!(notch_closing_radius >= 0))
    throw_input_error(where, "notch_closing_radius", "a length >= 0 mm", std::to_string(notch_closing_radius));
  if (!(chordae_opening_radius >= 0))
    throw_input_error(where, "chordae_opening_radius", "a length >= 0 mm", std::to_string(chordae_opening_radius));
  if (!(min_component_mm3 >= 0)) throw_input_error(where, "min_component_mm3", "a volume >= 0", std::to_string(min_component_mm3));
  if (!(max_foreground_fraction > 0 && max_foreground_fraction <= 1))
    throw_input_error(where, "max_foreground_fraction", "a fraction in (0, 1]", std::to_string(max_foreground_fraction));
  if (crop && !(crop_hi.array() > crop_lo.array()).all()) throw_input_error(where, "crop", "a box with max > min on every axis", "an empty box");
}

LabelMap segment_valve(const Volume& volume, const SegmentationOptions& o, SegmentationSummary* summary) {
  o.validate("segmentation");
  SegmentationSummary s;
  const ImageGeometry& g0 = volume.geometry;
  const double ratio = g0.spacing.maxCoeff() / g0.spacing.minCoeff();
  if (ratio > o.max_spacing_ratio) {
    char found[128];
    std::snprintf(found, sizeof found, "%.3g x %.3g x %.3g mm (ratio %.1f)", g0.spacing.x(), g0.spacing.y(), g0.spacing.z(), ratio);
    throw_input_error("segmentation", "spacing", "voxels with largest/smallest spacing <= " + std::to_string(o.max_spacing_ratio).substr(0, 4) + " (resample first)", found);
  }

  FloatImage::Pointer image = crop(volume_to_itk<float>(volume), o, g0);
  const ImageGeometry g = itk_geometry(*image);
  s.cropped = g;
  image = denoise(image, o);

  if (o.threshold_method == "otsu") {
    auto otsu = itk::OtsuThresholdImageFilter<FloatImage, MaskImage>::New();
    otsu->SetInput(image);
    otsu->SetNumberOfHistogramBins(256);
    otsu->Update();
    s.threshold = otsu->GetThreshold();
  } else {
    s.threshold = o.threshold;
  }
  auto binarize = itk::BinaryThresholdImageFilter<FloatImage, MaskImage>::New();
  binarize->SetInput(image);
  binarize->SetLowerThreshold(static_cast<float>(s.threshold));
  binarize->SetInsideValue(1);
  binarize->SetOutsideValue(0);
  binarize->Update();
  MaskImage::Pointer tissue = binarize->GetOutput();

  const std::size_t n = g.voxel_count();
  auto count = [n](const MaskImage* m) {
    const auto* p = m->GetBufferPointer();
    return static_cast<std::size_t>(std::count(p, p + n, std::uint8_t(1)));
  };
  const std::size_t raw = count(tissue);
  char thr[64];
  std::snprintf(thr, sizeof thr, "%.4g", s.threshold);
  if (raw == 0) throw_input_error("segmentation", "threshold", "tissue brighter than the threshold", std::string("no voxel above ") + thr + " (empty segmentation)");
  if (raw > o.max_foreground_fraction * n) {
    char found[128];
    std::snprintf(found, sizeof found, "threshold %s keeps %.0f %% of the voxels", thr, 100.0 * raw / n);
    throw_input_error("segmentation", "threshold", "a threshold separating tissue from background (at most " +
                      std::to_string(int(100 * o.max_foreground_fraction)) + " % tissue)", found);
  }

  Ball ball;
  if (o.closing_radius > 0 && ball_of(o.closing_radius, g, &ball))
    tissue = morphology<itk::BinaryMorphologicalClosingImageFilter>(tissue, ball);
  s.voxels_tissue = count(tissue);

  MaskImage::Pointer core = tissue;
  double chord_radius = o.chordae_opening_radius;
  if (o.chordae_method == "hessian") {
    s.chordae_separated = true;
    chord_radius = o.tube_scale;
    const MaskImage::Pointer tubes = tube_voxels(image, tissue, g, o);
    core = empty_mask(g);
    const std::uint8_t *t = tissue->GetBufferPointer(), *tube = tubes->GetBufferPointer();
    std::uint8_t* c = core->GetBufferPointer();
    for (std::size_t v = 0; v < n; ++v) c[v] = t[v] && !tube[v];
  } else {
    s.chordae_separated = o.chordae_opening_radius > 0 && ball_of(o.chordae_opening_radius, g, &ball);
    if (s.chordae_separated) core = morphology<itk::BinaryMorphologicalOpeningImageFilter>(tissue, ball);
  }
  const double voxel_mm3 = g.spacing.prod();
  const auto min_voxels = static_cast<std::size_t>(std::ceil(o.min_component_mm3 / voxel_mm3));
  LabelImage::Pointer parts = components(core, std::max<std::size_t>(min_voxels, 1), false);
  const std::uint32_t* part = parts->GetBufferPointer();
  s.components = static_cast<int>(*std::max_element(part, part + n));
  if (s.components == 0) throw_input_error("segmentation", "threshold", "tissue pieces larger than min_component_mm3", "only noise-sized pieces");

  std::set<std::uint32_t> leaflet_parts;
  if (o.seeds.empty()) {
    leaflet_parts.insert(1);  // the largest
  } else {
    for (const Vec3& seed : o.seeds) {
      const Vec3 ci = g.continuous_index(seed);
      const long i = std::lround(ci.x()), j = std::lround(ci.y()), k = std::lround(ci.z());
      if (i < 0 || j < 0 || k < 0 || i >= g.size[0] || j >= g.size[1] || k >= g.size[2])
        throw_input_error("segmentation", "seeds", "seed points inside the (cropped) image", format_point(seed));
      // The nearest component label within 2 voxels: seeds are picked on thin sheets.
      std::uint32_t found = 0;
      double best = 1e300;
      for (long dk = -2; dk <= 2; ++dk)
        for (long dj = -2; dj <= 2; ++dj)
          for (long di = -2; di <= 2; ++di) {
            const long a = i + di, b = j + dj, c = k + dk;
            if (a < 0 || b < 0 || c < 0 || a >= g.size[0] || b >= g.size[1] || c >= g.size[2]) continue;
            const std::uint32_t l = part[g.linear_index(int(a), int(b), int(c))];
            const double d2 = double(di * di + dj * dj + dk * dk);
            if (l != 0 && d2 < best) best = d2, found = l;
          }
      if (found == 0) throw_input_error("segmentation", "seeds", "seed points on the leaflet tissue", format_point(seed) + " lies in the background");
      leaflet_parts.insert(found);
    }
  }
  s.leaflet_components = static_cast<int>(leaflet_parts.size());

  LabelMap out{g, std::vector<std::uint8_t>(n, label_background)};
  for (std::size_t v = 0; v < n; ++v)
    if (part[v] != 0) out.labels[v] = leaflet_parts.count(part[v]) ? label_leaflet : label_other_tissue;

  if (s.chordae_separated) {
    // What the opening removed: large pieces are chordae, crumbs return to the leaflet.
    const MaskImage::Pointer residual = empty_mask(g);
    std::uint8_t* r = residual->GetBufferPointer();
    const std::uint8_t* t = tissue->GetBufferPointer();
    const std::uint8_t* c = core->GetBufferPointer();
    for (std::size_t v = 0; v < n; ++v) r[v] = (t[v] && !c[v]) ? 1 : 0;
    LabelImage::Pointer pieces = components(residual, 1, true);
    const std::uint32_t* piece = pieces->GetBufferPointer();
    const std::uint32_t piece_count = n ? *std::max_element(piece, piece + n) : 0;
    std::vector<std::size_t> piece_size(piece_count + 1, 0);
    for (std::size_t v = 0; v < n; ++v) ++piece_size[piece[v]];
    // A chord piece is at least 16 chord radii long: π r² · 16 r worth of voxels (r: the
    // opening radius, or the Hessian's scale).
    const double radius = chord_radius;
    const auto chord_min = static_cast<std::size_t>(std::ceil(16 * 3.14159 * radius * radius * radius / voxel_mm3));
    std::vector<char> is_chord(piece_count + 1, 0);
    for (std::uint32_t p = 1; p <= piece_count; ++p)
      if (piece_size[p] >= chord_min) is_chord[p] = 1, ++s.chordae_pieces;
    for (std::size_t v = 0; v < n; ++v) {
      if (!piece[v]) continue;
      if (is_chord[piece[v]]) out.labels[v] = label_chordae;
      else if (out.labels[v] == label_background) out.labels[v] = label_leaflet;
    }
  }
  if (o.chordae_method == "hessian" && o.notch_closing_radius > 0 && ball_of(o.notch_closing_radius, g, &ball)) {
    // Without this the remeshed TTV membrane keeps the notches as a ragged free edge
    // (minimum triangle quality 0.12 instead of 0.68).
    const MaskImage::Pointer leaflet = empty_mask(g);
    std::uint8_t* l = leaflet->GetBufferPointer();
    for (std::size_t v = 0; v < n; ++v) l[v] = out.labels[v] == label_leaflet;
    const MaskImage::Pointer closed = morphology<itk::BinaryMorphologicalClosingImageFilter>(leaflet, ball);
    const std::uint8_t* c = closed->GetBufferPointer();
    for (std::size_t v = 0; v < n; ++v)
      if (c[v] && out.labels[v] == label_chordae) out.labels[v] = label_leaflet;  // notches only, not other tissue
  }
  for (std::uint8_t l : out.labels) {
    if (l == label_leaflet) ++s.voxels_leaflet;
    else if (l == label_chordae) ++s.voxels_chordae;
    else if (l == label_other_tissue) ++s.voxels_other;
  }
  if (summary) *summary = s;
  return out;
}

}  // namespace valve
