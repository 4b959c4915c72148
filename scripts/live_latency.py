#!/usr/bin/python3
"""Latency of the live graph from a bag recorded while another bag played into it (scripts/benchmark_live):
pairs every /odometry message with the /camera/camera_info message of the same stamp (played together
with its image) and reports, per frame, how long after its image the pose arrived. A graph that keeps
up holds its latency; one that falls behind adds to it frame after frame, until its queues overflow.

  live_latency.py RECORDED_BAG --rate R [--steal S] [--label L] [--camera-info TOPIC] [--odometry TOPIC]
                  [--json FILE] [--frames-file FILE]

Prints one summary line; --json writes the figures, --frames-file the per-frame latencies."""
import argparse
import json
import statistics
import sys

import rosbag

# Frames whose pose the initialisation releases in one burst after it succeeds (KITTI: about 12):
# their latency is the initialisation's, not the graph's steady state.
DEFAULT_SKIP = 15


def slope(values):
    """Least-squares slope of values over their index (ms per frame)."""
    n = len(values)
    if n < 2:
        return 0.0
    mean_x = (n - 1) / 2.0
    mean_y = sum(values) / n
    sxx = sum((i - mean_x) ** 2 for i in range(n))
    return sum((i - mean_x) * (v - mean_y) for i, v in enumerate(values)) / sxx


def analyse(path, rate, camera_info_topic, odometry_topic, skip):
    played = {}  # stamp -> receipt time of the frame's camera_info
    poses = []  # (stamp, receipt time) of each odometry message
    with rosbag.Bag(path) as bag:
        for topic, message, received in bag.read_messages(topics=[camera_info_topic, odometry_topic]):
            stamp = message.header.stamp.to_nsec()
            if topic == camera_info_topic:
                played.setdefault(stamp, received.to_sec())
            else:
                poses.append((stamp, received.to_sec()))
    if not played:
        raise ValueError("%s holds no %s message: was the bag playing?" % (path, camera_info_topic))
    frame_of = {stamp: i for i, stamp in enumerate(sorted(played))}
    latency = {}  # frame index -> ms
    for stamp, received in poses:
        if stamp in frame_of:
            latency.setdefault(frame_of[stamp], 1e3 * (received - played[stamp]))
    steady = [latency[i] for i in sorted(latency) if i >= skip]
    stamps = sorted(played)
    if len(stamps) < 2 or stamps[-1] <= stamps[0]:
        raise ValueError("%s: fewer than two frames played, no frame period" % path)
    period_ms = 1e-6 * (stamps[-1] - stamps[0]) / (len(stamps) - 1) / rate  # wall time between played frames
    trend = slope(steady)
    # Falling behind by `trend` ms a frame, the graph takes period + trend per frame.
    sustained = 1e3 / (period_ms + trend) if trend > 0 else 1e3 / period_ms
    return {
        "rate": rate,
        "played_hz": 1e3 / period_ms,
        "frames_played": len(played),
        "poses": len(latency),
        "frames_without_pose": len(played) - len(latency),
        "steady_frames": len(steady),
        "latency_median_ms": statistics.median(steady) if steady else None,
        "latency_max_ms": max(steady) if steady else None,
        "latency_last_ms": steady[-1] if steady else None,
        "latency_trend_ms_per_frame": trend,
        "sustained_hz": sustained,
        "latency_ms": [latency.get(i) for i in range(len(played))],
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("bag")
    parser.add_argument("--rate", type=float, required=True, help="rosbag play rate the bag was played at")
    parser.add_argument("--steal", type=float, default=None, help="share of CPU time the hypervisor took, percent")
    parser.add_argument("--label", default="", help="name of the run in the summary line")
    parser.add_argument("--camera-info", default="/camera/camera_info")
    parser.add_argument("--odometry", default="/odometry")
    parser.add_argument("--skip", type=int, default=DEFAULT_SKIP, help="first frames left out of the steady state")
    parser.add_argument("--json", default=None)
    parser.add_argument("--frames-file", default=None)
    args = parser.parse_args()
    try:
        result = analyse(args.bag, args.rate, args.camera_info, args.odometry, args.skip)
    except (ValueError, rosbag.ROSBagException) as error:
        print("live_latency: %s" % error, file=sys.stderr)
        return 1
    result["label"] = args.label
    result["steal_percent"] = args.steal
    median = result["latency_median_ms"]
    keeps_up = result["frames_without_pose"] == 0 and result["latency_trend_ms_per_frame"] < 0.05 * 1e3 / result["played_hz"]
    result["keeps_up"] = keeps_up
    print("%s %.2fx (%.1f Hz): %d/%d frames with a pose; latency after frame %d: median %s ms, max %s ms, "
          "trend %+.1f ms/frame -> %s%s" % (
              args.label, args.rate, result["played_hz"], result["poses"], result["frames_played"], args.skip,
              "%.0f" % median if median is not None else "-",
              "%.0f" % result["latency_max_ms"] if result["latency_max_ms"] is not None else "-",
              result["latency_trend_ms_per_frame"],
              "keeps up" if keeps_up else "falls behind (sustains about %.1f Hz)" % result["sustained_hz"],
              "" if args.steal is None else "; hypervisor took %.0f %% of the CPU time" % args.steal))
    if args.json:
        with open(args.json, "w") as out:
            json.dump(result, out, indent=1)
    if args.frames_file:
        with open(args.frames_file, "w") as out:
            out.write("# frame latency_ms (empty: no pose)\n")
            for i, value in enumerate(result["latency_ms"]):
                out.write("%d %s\n" % (i, "" if value is None else "%.1f" % value))
    return 0


if __name__ == "__main__":
    sys.exit(main())
