#!/usr/bin/python3
"""Latency of the live graph from a bag recorded while another bag played into it (scripts/benchmark_live):
pairs every /odometry message with the /camera/camera_info message of the same stamp (played together
with its image) and reports, per frame, how long after its image the pose arrived. A graph that keeps
up holds its latency; one that falls behind adds to it frame after frame, until its queues overflow.
From /tracking_status it adds the frames trusted and the class maps' age (a live segmenter's maps
carried to the frames after theirs), from /segmentation_time the frames segmented and their time.

  live_latency.py RECORDED_BAG --rate R [--steal S] [--label L] [--camera-info TOPIC] [--odometry TOPIC]
                  [--json FILE] [--frames-file FILE]
  live_latency.py --table JSON...   (Markdown rows: one per run, then one per rate over its runs)

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
    statuses = []  # (state, class map age s) of each tracking status
    segmentation_ms = []
    with rosbag.Bag(path) as bag:
        for topic, message, received in bag.read_messages(
                topics=[camera_info_topic, odometry_topic, "/tracking_status", "/segmentation_time"]):
            if topic == "/segmentation_time":
                segmentation_ms.append(message.data)
                continue
            stamp = message.header.stamp.to_nsec()
            if topic == camera_info_topic:
                played.setdefault(stamp, received.to_sec())
            elif topic == odometry_topic:
                poses.append((stamp, received.to_sec()))
            else:
                statuses.append((message.state, getattr(message, "class_map_age", -1.0)))
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
    ages = [age for _, age in statuses if age >= 0]
    behind = trend >= 0.05 * period_ms  # the latency grows by 5 % of a frame period a frame, or more
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
        "keeps_up": len(latency) == len(played) and not behind,
        # Falling behind by `trend` ms a frame, the graph takes period + trend a frame (null: it did not).
        "sustained_hz": 1e3 / (period_ms + trend) if behind else None,
        "latency_ms": [latency.get(i) for i in range(len(played))],
        "statuses": len(statuses),
        "untrusted_or_lost": sum(state in (2, 4) for state, _ in statuses),  # TrackingStatus LOST, UNTRUSTED
        "class_map_age_median_s": statistics.median(ages) if ages else None,
        "class_map_age_max_s": max(ages) if ages else None,
        "frames_without_class_map": sum(age < 0 for _, age in statuses),
        "frames_segmented": len(segmentation_ms),
        "segmentation_median_ms": statistics.median(segmentation_ms) if segmentation_ms else None,
    }


def verdict(result):
    """What the run says about the graph, in words."""
    if result["keeps_up"]:
        return "keeps up"
    words = []
    if result["frames_without_pose"]:
        words.append("%d frames without a pose" % result["frames_without_pose"])
    if result["sustained_hz"] is not None:
        words.append("falls behind (sustains about %.1f Hz)" % result["sustained_hz"])
    return ", ".join(words)


def table(paths):
    """Markdown table of the runs in `paths` (latency.json files), then each rate's verdict over its runs."""
    runs = [json.load(open(path)) for path in paths]
    fmt = lambda v: "-" if v is None else "%.0f" % v
    age = lambda v: "-" if v is None else "%.2f" % v
    lines = ["| rate | played Hz | frames with a pose | median latency ms | max ms | trend ms/frame | verdict | "
             "class map age s, median / max | frames segmented, median ms | manager CPU, cores | hypervisor took |",
             "|---:|---:|---:|---:|---:|---:|---|---:|---:|---:|---:|"]
    for r in runs:
        lines.append("| %.2gx | %.1f | %d/%d | %s | %s | %+.1f | %s | %s / %s | %d, %s | %s | %s %% |" % (
            r["rate"], r["played_hz"], r["poses"], r["frames_played"], fmt(r["latency_median_ms"]),
            fmt(r["latency_max_ms"]), r["latency_trend_ms_per_frame"], verdict(r), age(r.get("class_map_age_median_s")),
            age(r.get("class_map_age_max_s")), r.get("frames_segmented", 0), fmt(r.get("segmentation_median_ms")),
            age(r.get("manager_cores")), fmt(r["steal_percent"])))
    lines.append("")
    for rate in sorted({r["rate"] for r in runs}):
        same = [r for r in runs if r["rate"] == rate]
        kept = sum(r["keeps_up"] for r in same)
        behind = [r["sustained_hz"] for r in same if r["sustained_hz"] is not None]
        lines.append("- %.2gx (%.1f Hz): keeps up in %d of %d runs; median over the runs: latency %s ms, trend %+.1f ms/frame%s" % (
            rate, same[0]["played_hz"], kept, len(same), fmt(statistics.median(r["latency_median_ms"] or 0.0 for r in same)),
            statistics.median(r["latency_trend_ms_per_frame"] for r in same),
            "; the runs that fell behind sustained %.1f Hz (median)" % statistics.median(behind) if behind else ""))
    return "\n".join(lines)


def main():
    if len(sys.argv) > 1 and sys.argv[1] == "--table":
        print(table(sys.argv[2:]))
        return 0
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("bag")
    parser.add_argument("--rate", type=float, required=True, help="rosbag play rate the bag was played at")
    parser.add_argument("--steal", type=float, default=None, help="share of CPU time the hypervisor took, percent")
    parser.add_argument("--manager-cores", type=float, default=None, help="CPU time of the nodelet manager over the wall time")
    parser.add_argument("--label", default="", help="name of the run in the summary line")
    parser.add_argument("--camera-info", default="/camera/camera_info")
    parser.add_argument("--odometry", default="/odometry")
    parser.add_argument("--skip", type=int, default=DEFAULT_SKIP, help="first frames left out of the steady state")
    parser.add_argument("--json", default=None)
    parser.add_argument("--frames-file", default=None)
    args = parser.parse_args()
    try:
        result = analyse(args.bag, args.rate, args.camera_info, args.odometry, args.skip)
    except (OSError, ValueError, rosbag.ROSBagException) as error:
        print("live_latency: %s" % error, file=sys.stderr)
        return 1
    result["label"] = args.label
    result["steal_percent"] = args.steal
    result["manager_cores"] = args.manager_cores
    median = result["latency_median_ms"]
    trend = result["latency_trend_ms_per_frame"]
    print("%s %.2fx (%.1f Hz): %d/%d frames with a pose; latency after frame %d: median %s ms, max %s ms, "
          "trend %+.1f ms/frame -> %s%s" % (
              args.label, args.rate, result["played_hz"], result["poses"], result["frames_played"], args.skip,
              "%.0f" % median if median is not None else "-",
              "%.0f" % result["latency_max_ms"] if result["latency_max_ms"] is not None else "-",
              trend, verdict(result), "" if args.steal is None else "; hypervisor took %.0f %% of the CPU time" % args.steal))
    if result["frames_segmented"] or result["class_map_age_median_s"] is not None:
        print("%s: %d frames segmented (median %s ms); class map age median %s s, max %s s; %d frames without a class map; "
              "%d untrusted or lost" % (
                  args.label, result["frames_segmented"], "%.0f" % result["segmentation_median_ms"] if result["segmentation_median_ms"] else "-",
                  "%.2f" % result["class_map_age_median_s"] if result["class_map_age_median_s"] is not None else "-",
                  "%.2f" % result["class_map_age_max_s"] if result["class_map_age_max_s"] is not None else "-",
                  result["frames_without_class_map"], result["untrusted_or_lost"]))
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
