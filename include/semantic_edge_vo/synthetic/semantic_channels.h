#pragma once
#include <cstdint>

#include <opencv2/core/mat.hpp>

namespace semantic_edge_vo {
namespace synthetic {

/// What a semantic edge network (CASENet-like) outputs for one image, in compact form.
/// The probability of an edge of class k at a pixel is edge_strength / 255 when bit k of
/// edge_classes is set there, else 0.
struct SemanticNetworkOutput {
  cv::Mat edge_strength;      ///< CV_8UC1, edge probability x 255 (the largest over the classes)
  cv::Mat edge_classes;       ///< CV_32SC1, bit k set: the edge belongs to class k (both sides at a boundary)
  cv::Mat class_probability;  ///< CV_8UC4: [most likely class, its probability x 255, second class, its probability x 255]

  /// A deep copy (copies of cv::Mat share their pixels).
  SemanticNetworkOutput clone() const { return {edge_strength.clone(), edge_classes.clone(), class_probability.clone()}; }
  /// Edge probability of class k at (x, y), in [0, 1].
  float edgeProbability(int k, int x, int y) const;
  /// Most likely class per pixel (CV_8UC1): channel 0 of class_probability.
  cv::Mat topClass() const;
  /// Its probability x 255 per pixel (CV_8UC1): channel 1 of class_probability.
  cv::Mat topConfidence() const;
};

/// A class that a network confuses class k with (road-sidewalk, building-wall, pole-sign, car-truck,
/// vegetation-terrain, ...), among the 19 Cityscapes training ids.
int confusableClass(int k);

/// The error-free network output of a frame: boundary edges where the ground-truth class changes
/// between 4-neighbours (both pixels, labelled with both classes, probability 1), texture edges
/// inside a class where the clean image has strong gradients (window frames, lane markings, joints;
/// probability up to 0.8, labelled with the class), and class probabilities (0.95 inside regions,
/// 0.6 / 0.4 shared with the other class on boundaries).
/// @param class_id CV_8UC1 ground-truth train ids
/// @param clean_gray CV_8UC1 image without sensor noise or exposure changes
SemanticNetworkOutput exactSemanticChannels(const cv::Mat& class_id, const cv::Mat& clean_gray);

}  // namespace synthetic
}  // namespace semantic_edge_vo
