#pragma once
#include <functional>
#include <string>
#include <vector>

#include <sensor_msgs/PointCloud2.h>

#include "semantic_edge_vo/SaveFiles.h"

namespace semantic_edge_vo {

/// The semantic edge map (the Mapping nodelet's cloud: x, y, z, label, rgb) as
/// `<directory>/semantic_edge_map.pcd` (PCL's ASCII PCD v0.7, fields x y z label rgb) and
/// `semantic_edge_map.ply` (ASCII PLY: x y z, red green blue, label), both with the class names of
/// the labels in comments. Returns the first error (empty: both written); `files` gets their paths.
std::string writeMapFiles(const sensor_msgs::PointCloud2& cloud, const std::vector<std::string>& class_names,
                          const std::string& directory, std::vector<std::string>* files);

/// Serves a SaveFiles request: makes the directory, runs `write` (which returns an error or empty
/// and names the files it wrote) and says what happened in the response.
bool serveSaveFiles(const SaveFiles::Request& request, SaveFiles::Response* response,
                    const std::function<std::string(const std::string& directory, std::vector<std::string>* files)>& write);

}  // namespace semantic_edge_vo
