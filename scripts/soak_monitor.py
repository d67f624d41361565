#!/usr/bin/python3
"""The watching half of scripts/soak.sh: a ROS node beside the charging demo that follows the
simulated clock through the robots' battery topics and records into OUT_DIR

  pids         node PID, once every expected node has registered with the master
  samples.csv  sim_s,node,rss_kb,cpu_s: each node's VmRSS and CPU time (user + system) so far at
               the scheduled simulated times (the monitor itself as /soak_monitor)
  batteries    robot min_level: the lowest battery level each robot reported
  events       sim_s what detail: a node gone while world_sim still ran (died), a battery at 0
               (flat), the node this run killed on purpose (killed, --kill-node)
  ready        written once it listens, before the demo starts (see below)

It must start before the demo sets /use_sim_time: with it unset rospy keeps wall time and does
not subscribe to /clock, which world_sim publishes every step (thousands a second in lockstep).
It ends when world_sim has gone, or on SIGTERM/SIGINT.
"""
import argparse
import os
import signal
import sys
import threading
import time
import xmlrpc.client

import rosgraph
import rospy
from sensor_msgs.msg import BatteryState

NAME = '/soak_monitor'
TICKS = os.sysconf('SC_CLK_TCK')


def parse_args():
    p = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    p.add_argument('--robots', type=int, required=True)
    p.add_argument('--duration', type=float, required=True, help='simulated s the demo runs')
    p.add_argument('--baseline', type=float, required=True, help='simulated s of the first RSS sample')
    p.add_argument('--interval', type=float, required=True, help='simulated s between RSS samples')
    p.add_argument('--out', required=True)
    p.add_argument('--register-timeout', type=float, default=120.0, help='wall s for every node to register')
    p.add_argument('--kill-node', default='', help='for the tests: SIGKILL this node ...')
    p.add_argument('--kill-at', type=float, default=0.0, help='... at this simulated time')
    return p.parse_args()


def expected_nodes(robots):
    names = ['/world_sim', '/audio_propagation']
    for k in range(robots):
        names += ['/robot_%d/local_mutex' % k, '/robot_%d/charging_demo' % k]
    return names


def rss_kb(pid):
    """VmRSS of a live process in kB; None when it has gone (or is a zombie)."""
    try:
        with open('/proc/%d/status' % pid) as f:
            fields = dict(line.split(':', 1) for line in f if ':' in line)
    except OSError:
        return None
    # A zombie, or a process on its way out (its memory already gone: no VmRSS line).
    if fields.get('State', '').strip().startswith('Z') or 'VmRSS' not in fields:
        return None
    return int(fields['VmRSS'].split()[0])


def cpu_s(pid):
    """User + system CPU time of a process so far, in s (0 when it has gone)."""
    try:
        with open('/proc/%d/stat' % pid) as f:
            fields = f.read().rsplit(')', 1)[1].split()  # after the command name, which may hold spaces
    except OSError:
        return 0.0
    return (int(fields[11]) + int(fields[12])) / TICKS


def alive(pid):
    return rss_kb(pid) is not None


class Monitor:
    def __init__(self, args):
        self.args = args
        self.lock = threading.Lock()
        self.sim_time = 0.0
        self.min_battery = {}
        self.flat = set()
        self.events = open(os.path.join(args.out, 'events'), 'w')
        self.samples = open(os.path.join(args.out, 'samples.csv'), 'w')
        self.samples.write('sim_s,node,rss_kb,cpu_s\n')
        self.pids = {}
        self.gone = set()
        self.stop = False
        self.subs = [rospy.Subscriber('/robot_%d/battery' % k, BatteryState, self.on_battery, 'robot_%d' % k,
                                      queue_size=100) for k in range(args.robots)]
        # The scheduled sample times: the baseline, every interval and one just before the end,
        # since the nodes stop with world_sim at `duration` and the end sample must find them.
        times = {args.baseline, max(args.baseline, args.duration - 1.0)}
        t = args.interval
        while t < args.duration:
            times.add(t)
            t += args.interval
        self.schedule = sorted(x for x in times if x >= args.baseline)

    def event(self, sim_s, what, detail):
        self.events.write('%.1f %s %s\n' % (sim_s, what, detail))
        self.events.flush()

    def on_battery(self, msg, robot):
        t = msg.header.stamp.to_sec()
        with self.lock:
            self.sim_time = max(self.sim_time, t)
            level = msg.percentage
            if robot not in self.min_battery or level < self.min_battery[robot]:
                self.min_battery[robot] = level
            if level <= 0.0 and robot not in self.flat:
                self.flat.add(robot)
                self.event(t, 'flat', robot)

    def find_pids(self):
        master = rosgraph.Master(NAME)
        deadline = time.monotonic() + self.args.register_timeout
        wanted = expected_nodes(self.args.robots)
        while not self.stop:
            missing = [n for n in wanted if n not in self.pids]
            for node in missing:
                try:
                    code, _, pid = xmlrpc.client.ServerProxy(master.lookupNode(node)).getPid(NAME)
                except Exception:  # not registered yet, or not answering yet
                    continue
                if code == 1:
                    self.pids[node] = pid
            if len(self.pids) == len(wanted):
                break
            if time.monotonic() > deadline:
                sys.exit('soak_monitor: after %.0f s these nodes have not registered: %s'
                         % (self.args.register_timeout, ' '.join(n for n in wanted if n not in self.pids)))
            time.sleep(0.2)
        with open(os.path.join(self.args.out, 'pids'), 'w') as f:
            for node in wanted:
                f.write('%s %d\n' % (node, self.pids.get(node, 0)))

    def check_deaths(self, now):
        # A node counts as died only if world_sim is still there after its PID has gone: at the
        # end world_sim leaves first and roslaunch then stops the others.
        gone = [n for n, pid in self.pids.items() if n not in self.gone and not alive(pid)]
        if not gone:
            return True
        world_alive = alive(self.pids['/world_sim'])
        for node in gone:
            self.gone.add(node)
            if world_alive:
                self.event(now, 'died', node)
        return world_alive

    def sample(self, now):
        for node, pid in list(self.pids.items()) + [(NAME, os.getpid())]:
            rss, cpu = rss_kb(pid), cpu_s(pid)
            if rss is not None:
                self.samples.write('%.1f,%s,%d,%.2f\n' % (now, node, rss, cpu))
        self.samples.flush()

    def run(self):
        open(os.path.join(self.args.out, 'ready'), 'w').close()
        self.find_pids()
        next_sample = 0
        killed = False
        while not self.stop and not rospy.is_shutdown():
            with self.lock:
                now = self.sim_time
            if not self.check_deaths(now):
                break
            if self.args.kill_node and not killed and now >= self.args.kill_at:
                killed = True
                pid = self.pids.get(self.args.kill_node)
                if pid is None:
                    sys.exit('soak_monitor: --kill-node %s: no such node (known: %s)'
                             % (self.args.kill_node, ' '.join(sorted(self.pids))))
                os.kill(pid, signal.SIGKILL)
                self.event(now, 'killed', self.args.kill_node)
            taken = False
            while next_sample < len(self.schedule) and now >= self.schedule[next_sample]:
                next_sample += 1
                taken = True
            if taken:
                self.sample(now)
            time.sleep(0.05)
        with open(os.path.join(self.args.out, 'batteries'), 'w') as f:
            with self.lock:
                for robot in sorted(self.min_battery):
                    f.write('%s %.3f\n' % (robot, self.min_battery[robot]))


def main():
    args = parse_args()
    rospy.init_node(NAME.lstrip('/'), disable_signals=True)
    monitor = Monitor(args)

    def stop(*_):
        monitor.stop = True
    signal.signal(signal.SIGTERM, stop)
    signal.signal(signal.SIGINT, stop)
    monitor.run()
    rospy.signal_shutdown('done')


if __name__ == '__main__':
    main()
