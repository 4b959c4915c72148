#!/usr/bin/python3
"""Prints what the odometry published, from a bag recorded by scripts/demo: messages and rate per
topic, tracking states, map and path sizes. Usage: summarize_bag.py BAG"""
import collections
import sys

import rosbag

STATES = {0: "INITIALIZING", 1: "TRACKING", 2: "LOST", 3: "RECOVERED", 4: "UNTRUSTED"}


def main(path):
    stamps = collections.defaultdict(list)
    states = collections.Counter()
    last = {}
    with rosbag.Bag(path) as bag:
        for topic, message, _ in bag.read_messages():
            header = getattr(message, "header", None)
            if header is not None:
                stamps[topic].append(header.stamp.to_sec())
            last[topic] = message
            if topic.endswith("tracking_status"):
                states[STATES.get(message.state, str(message.state))] += 1
    print("topic                          messages   rate (Hz)")
    for topic in sorted(stamps):
        times = stamps[topic]
        rate = (len(times) - 1) / (times[-1] - times[0]) if len(times) > 1 and times[-1] > times[0] else 0.0
        print("  %-28s %8d   %8.2f" % (topic, len(times), rate))
    if states:
        print("tracking states: " + ", ".join("%s %d" % item for item in sorted(states.items())))
    for topic, message in last.items():
        if topic.endswith("semantic_edge_map"):
            print("semantic edge map: %d points (fields: %s)" % (message.width * message.height,
                                                              ", ".join(f.name for f in message.fields)))
        if topic.endswith("path"):
            print("path: %d poses in frame '%s'" % (len(message.poses), message.header.frame_id))
    if not stamps:
        print("the bag holds no message")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
