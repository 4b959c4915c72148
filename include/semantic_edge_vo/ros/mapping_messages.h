#pragma once
// The messages between the Tracking and Mapping nodelets: the core's mapping requests and outcomes,
// passed as shared pointers inside one nodelet manager (they hold frames and keyframes, which have
// no wire format). A subscriber in another process receives them empty; the nodelets reject those.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <boost/shared_ptr.hpp>
#include <ros/message_traits.h>
#include <ros/serialization.h>
#include <ros/time.h>

#include "semantic_edge_vo/backend/mapper.h"
#include "semantic_edge_vo/backend/odometry_options.h"
#include "semantic_edge_vo/common/camera.h"

namespace semantic_edge_vo {

/// Tracking -> Mapping: one request of an odometry (a session).
struct MappingRequestMessage {
  /// One per odometry: a request of a new session makes the Mapping nodelet start a new mapper
  /// with the session's options and camera.
  std::uint64_t session = 0;
  std::shared_ptr<const OdometryOptions> options;
  PinholeCamera camera;
  ros::Time stamp;  ///< of the request's frame
  std::vector<std::string> class_names;  ///< the intake's class table (the map's colours)
  MappingRequest request;
};

/// Mapping -> Tracking: one outcome of a session's request.
struct MappingOutcomeMessage {
  std::uint64_t session = 0;
  ros::Time stamp;  ///< of the outcome's frame
  MappingOutcome outcome;
};

}  // namespace semantic_edge_vo

// What roscpp needs to publish and subscribe them; nothing crosses a process boundary.
#define SEMANTIC_EDGE_VO_IN_PROCESS_MESSAGE(TYPE, NAME, MD5)                                                      \
  namespace ros {                                                                                                 \
  namespace message_traits {                                                                                      \
  template <>                                                                                                     \
  struct IsMessage<TYPE> : TrueType {};                                                                           \
  template <>                                                                                                     \
  struct MD5Sum<TYPE> {                                                                                           \
    static const char* value() { return MD5; }                                                                    \
    static const char* value(const TYPE&) { return value(); }                                                     \
  };                                                                                                              \
  template <>                                                                                                     \
  struct DataType<TYPE> {                                                                                         \
    static const char* value() { return NAME; }                                                                   \
    static const char* value(const TYPE&) { return value(); }                                                     \
  };                                                                                                              \
  template <>                                                                                                     \
  struct Definition<TYPE> {                                                                                       \
    static const char* value() { return "# in-process only: shared between the nodelets of one manager\n"; }     \
    static const char* value(const TYPE&) { return value(); }                                                     \
  };                                                                                                              \
  }                                                                                                               \
  namespace serialization {                                                                                       \
  template <>                                                                                                     \
  struct Serializer<TYPE> {                                                                                       \
    template <typename Stream, typename T>                                                                        \
    inline static void allInOne(Stream&, T) {}                                                                    \
    ROS_DECLARE_ALLINONE_SERIALIZER                                                                               \
  };                                                                                                              \
  }                                                                                                               \
  }

SEMANTIC_EDGE_VO_IN_PROCESS_MESSAGE(semantic_edge_vo::MappingRequestMessage, "semantic_edge_vo/MappingRequestInProcess",
                                    "6c1d6f3b8a0e4d2f9b7a5c3e1f0d2b4a")
SEMANTIC_EDGE_VO_IN_PROCESS_MESSAGE(semantic_edge_vo::MappingOutcomeMessage, "semantic_edge_vo/MappingOutcomeInProcess",
                                    "0f2e4c6a8b1d3f5e7a9c0b2d4f6e8a1c")
#undef SEMANTIC_EDGE_VO_IN_PROCESS_MESSAGE
