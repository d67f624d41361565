#!/usr/bin/python3
"""Waits, for scripts/screenshots.sh, until a running demo shows what its picture is meant to
show, then stops the simulated clock by sending SIGSTOP to world_sim: rviz keeps drawing that
moment (markers do not expire while /clock stands still) for as long as the capture takes.

  screenshot_moment.py SCENE --robots N --count K --after T --timeout S --freeze PID
                       [--hold H] [--fallback K2 --fallback-after T2] [--within X0 Y0 X1 Y1]

SCENE is what has to be on screen, K how much of it:
  paths   K sound paths that bend round a corner drawn at once (/audio_propagation/paths), and
          every drawn path in the box --within (map frame, m) when it is given: the view
  plans   K explorers with a plan of two poses or more (/robot_k/sounds_good_explorer/plan)
  queue   K charging robots in phase "wait" and wanting the lock (WANTED or SILENT) while
          another docks or charges (/robot_k/charging_demo/state), and the labels of these
          robots clear of every other label (/robot_k/charging_demo/charger, TF)
never before T s of simulated time, and (with --hold) only once the scene has lasted H simulated
s, so that rviz has drawn every robot's latest markers for it. From T2 s of simulated time on,
K2 is enough: a second best that comes often, for a best that may not come at all. Prints what
it saw and exits 0 once world_sim is stopped; exits 1 with one line on stderr if S s of wall
time pass first. The caller sends SIGCONT.
"""
import argparse
import math
import os
import signal
import sys
import threading
import time

import rospy
import tf2_ros
from multirobot_audio.msg import ChargingState, LockState
from nav_msgs.msg import Path
from visualization_msgs.msg import MarkerArray


class Paths:
    """Sound paths still drawn; a path with a corner (three points or more) is bent. With a box,
    a moment counts only while every drawn path lies in it, so that none leaves the view."""

    def __init__(self, robots, within):
        self.within = within
        self.drawn = []  # (expiry in simulated s, sender, corner points, inside the box)
        self.lock = threading.Lock()  # the subscriber's thread adds, the main thread prunes
        rospy.Subscriber("/audio_propagation/paths", MarkerArray, self.on_paths, queue_size=10)

    def inside(self, p):
        x0, y0, x1, y1 = self.within or (-1e9, -1e9, 1e9, 1e9)
        return x0 <= p.x <= x1 and y0 <= p.y <= y1

    def on_paths(self, msg):
        for m in msg.markers:
            corners = ["(%.1f, %.1f)" % (p.x, p.y) for p in m.points[1:-1]]
            inside = all(self.inside(p) for p in m.points)
            with self.lock:
                self.drawn.append((m.header.stamp.to_sec() + m.lifetime.to_sec(), m.ns, corners, inside))

    def count(self, now):
        with self.lock:
            self.drawn = [d for d in self.drawn if d[0] > now]
            if not all(d[3] for d in self.drawn):
                return 0
            return sum(1 for d in self.drawn if d[2])

    def describe(self):
        with self.lock:
            return "; ".join("%s's path bends at %s" % (ns, " ".join(c)) for _, ns, c, _ in self.drawn if c)


class Plans:
    """Explorers whose latest plan, at most 5 simulated s old, has two poses or more."""

    def __init__(self, robots, within):
        self.latest = {}  # robot -> (received at, poses)
        for k in range(robots):
            name = "robot_%d" % k
            rospy.Subscriber("/%s/sounds_good_explorer/plan" % name, Path,
                             lambda msg, n=name: self.latest.__setitem__(
                                 n, (rospy.get_time(), len(msg.poses))))

    def planning(self, now):
        return sorted(n for n, (t, poses) in self.latest.items() if poses >= 2 and now - t < 5.0)

    def count(self, now):
        return len(self.planning(now))

    def describe(self):
        now = rospy.get_time()
        return "plans of %s" % ", ".join("%s (%d poses)" % (n, self.latest[n][1]) for n in self.planning(now))


class Queue:
    """Robots waiting for the charger's lock while another one uses the charger. A robot in
    phase wait whose lock is RELEASED has not asked yet (or gave up): not in the queue. Robots
    waiting side by side write their labels over each other: the moment counts only while the
    labels of the robots in the queue and at the charger stand clear of every other label."""

    LABEL_WIDTH = 2.0   # m: "robot_k: phase LOCK battery" in 0.16 m letters, with a margin
    LABEL_HEIGHT = 0.2  # m

    def __init__(self, robots, within):
        self.state = {}   # robot -> ChargingState
        self.labels = {}  # robot -> (odometry frame, x, y) of its label
        self.tf = tf2_ros.Buffer()
        self.tf_listener = tf2_ros.TransformListener(self.tf)
        for k in range(robots):
            name = "robot_%d" % k
            rospy.Subscriber("/%s/charging_demo/state" % name, ChargingState,
                             lambda msg, n=name: self.state.__setitem__(n, msg))
            rospy.Subscriber("/%s/charging_demo/charger" % name, MarkerArray,
                             lambda msg, n=name: self.on_markers(n, msg))

    def on_markers(self, name, msg):
        for m in msg.markers:
            if m.ns == "label":
                self.labels[name] = (m.header.frame_id, m.pose.position.x, m.pose.position.y)

    def label_positions(self):
        """Where the labels stand on the map (rviz draws them through TF)."""
        out = {}
        for name, (frame, x, y) in list(self.labels.items()):
            try:
                t = self.tf.lookup_transform("map", frame, rospy.Time(0)).transform
            except tf2_ros.TransformException:
                continue
            yaw = 2.0 * math.atan2(t.rotation.z, t.rotation.w)
            out[name] = (t.translation.x + math.cos(yaw) * x - math.sin(yaw) * y,
                         t.translation.y + math.sin(yaw) * x + math.cos(yaw) * y)
        return out

    def overlap(self, a, b):
        return abs(a[0] - b[0]) < self.LABEL_WIDTH and abs(a[1] - b[1]) < self.LABEL_HEIGHT

    def count(self, now):
        asking = (LockState.WANTED, LockState.SILENT)
        waiting = [n for n, s in self.state.items() if s.phase == "wait" and s.lock in asking]
        using = [n for n, s in self.state.items() if s.phase in ("dock", "charge")]
        if not using:
            return 0
        at = self.label_positions()
        for n in waiting + using:
            if n not in at or any(self.overlap(at[n], p) for other, p in at.items() if other != n):
                return 0
        return len(waiting)

    def describe(self):
        locks = ["RELEASED", "WANTED", "SILENT", "HELD"]
        return ", ".join("%s %s %s (battery %.2f)" % (n, s.phase, locks[s.lock] if s.lock < 4 else s.lock, s.battery)
                         for n, s in sorted(self.state.items()))


SCENES = {"paths": Paths, "plans": Plans, "queue": Queue}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scene", choices=sorted(SCENES))
    parser.add_argument("--robots", type=int, required=True)
    parser.add_argument("--count", type=int, default=1)
    parser.add_argument("--after", type=float, default=0.0, help="simulated s")
    parser.add_argument("--timeout", type=float, required=True, help="wall s")
    parser.add_argument("--freeze", type=int, required=True, help="world_sim's pid")
    parser.add_argument("--hold", type=float, default=0.0, help="simulated s")
    parser.add_argument("--fallback", type=int, help="K2")
    parser.add_argument("--fallback-after", type=float, default=0.0, help="simulated s")
    parser.add_argument("--within", type=float, nargs=4, metavar=("X0", "Y0", "X1", "Y1"))
    args = parser.parse_args(rospy.myargv()[1:])

    rospy.init_node("screenshot_moment", anonymous=True, disable_signals=True)
    scene = SCENES[args.scene](args.robots, args.within)
    deadline = time.monotonic() + args.timeout
    since = None  # simulated s since when the scene has been on screen
    while time.monotonic() < deadline:
        now = rospy.get_time()
        wanted = args.count
        if args.fallback is not None and now >= args.fallback_after:
            wanted = args.fallback
        if now < args.after or scene.count(now) < wanted:
            since = None
        elif since is None:
            since = now
        if since is not None and now - since >= args.hold:
            os.kill(args.freeze, signal.SIGSTOP)
            print("screenshot_moment: %s (%d wanted) at %.1f s: %s" % (args.scene, wanted, now, scene.describe()))
            return 0
        time.sleep(0.05)
    print("screenshot_moment: no %s scene (%d wanted) after %.0f s of wall time, at %.1f s simulated"
          % (args.scene, args.count, args.timeout, rospy.get_time()), file=sys.stderr)
    return 1


if __name__ == "__main__":
    sys.exit(main())
