#!/usr/bin/python3
"""The judging half of scripts/soak.sh (no ROS): reads the demo's roslaunch log and what
scripts/soak_monitor.py recorded, prints the per-node table (resident memory at the baseline and
at the end, growth), every node's exit counters, the robots' lowest battery levels and the nodes
that died, and exits 1 if a node died, a robot ran flat, the run stopped short, world_sim dropped
a participant from the lockstep, a node printed no summary, or a node's memory grew by more than
--max-growth percent after the baseline.
"""
import argparse
import csv
import os
import re
import sys

SUMMARY = re.compile(r'^(world_sim|audio_propagation|charging_demo|local_mutex) (summary|timing): (.*)$')
DIED = re.compile(r'\[([^\[\]\s]+)-\d+\] process has died \[pid (\d+), exit code (-?\d+)')
COLOUR = re.compile(r'\x1b\[[0-9;]*m')  # roslaunch colours its own lines
SIMULATED = re.compile(r'simulated ([\d.]+) s')
DROPPED = re.compile(r'dropped (\d+)')
MONITOR = '/soak_monitor'  # soak_monitor.py's own row in samples.csv


def parse_args():
    p = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    p.add_argument('--log', required=True, help="the demo's roslaunch output")
    p.add_argument('--dir', required=True, help="soak_monitor.py's output folder")
    p.add_argument('--duration', type=float, required=True, help='simulated s asked for')
    p.add_argument('--baseline', type=float, required=True, help='simulated s of the baseline sample')
    p.add_argument('--max-growth', type=float, required=True, help='percent of RSS growth allowed after it')
    p.add_argument('--wall', type=float, required=True, help='wall s the demo took')
    return p.parse_args()


def node_of(program, text):
    """The node a summary line belongs to. local_mutex names its robot id, which
    launch/include/charging_team.launch sets to k + 1 for robot_k."""
    if program in ('world_sim', 'audio_propagation'):
        return '/' + program
    if program == 'charging_demo':
        return text.split()[0] + '/charging_demo'
    m = re.match(r'robot (\d+),', text)
    return '/robot_%d/local_mutex' % (int(m.group(1)) - 1) if m else '/?/local_mutex'


def read_log(path):
    counters, died = {}, {}
    with open(path, errors='replace') as f:
        for line in f:
            line = COLOUR.sub('', line.rstrip('\n'))
            m = SUMMARY.match(line)
            if m:
                counters.setdefault(node_of(m.group(1), m.group(3)), []).append(line)
                continue
            m = DIED.search(line)
            if m:
                died['/' + m.group(1)] = 'roslaunch: process has died (exit code %s)' % m.group(3)
    return counters, died


def read_samples(path):
    """node -> [(sim_s, rss_kb, cpu_s)] in time order."""
    samples = {}
    if os.path.exists(path):
        with open(path) as f:
            for row in csv.DictReader(f):
                samples.setdefault(row['node'], []).append(
                    (float(row['sim_s']), int(row['rss_kb']), float(row['cpu_s'])))
    return samples


def read_lines(path):
    if not os.path.exists(path):
        return []
    with open(path) as f:
        return [line.split() for line in f if line.strip()]


def mb(kb):
    return '%.1f' % (kb / 1024.0)


def memory_table(nodes, samples, baseline, max_growth, failures):
    if baseline >= 3600.0:
        print('memory: VmRSS at the first simulated hour (%.0f s) and at the end' % baseline)
    else:
        print('memory: the run is shorter than 1 simulated hour, so the baseline is the first sample '
              'after a warm-up of %.0f s (simulated), not the first hour' % baseline)
    # CPU s: user + system time from the node's start to its last sample: where the wall time goes.
    print('%-26s %12s %12s %12s %9s %9s' % ('node', 'baseline MB', 'end MB', 'end at s', 'growth', 'CPU s'))
    for node in nodes:
        series = samples.get(node, [])
        if not series:
            print('%-26s %12s %12s %12s %9s %9s' % (node, '-', '-', '-', '-', '-'))
            failures.append('%s: no memory sample (it was gone before the baseline)' % node)
            continue
        (_, base, _), (end_s, end, cpu) = series[0], series[-1]
        growth = 100.0 * (end - base) / base
        print('%-26s %12s %12s %12.0f %+8.1f%% %9.0f' % (node, mb(base), mb(end), end_s, growth, cpu))
        if growth > max_growth:
            failures.append('%s: resident memory grew %.1f %% after the baseline (limit %g %%)'
                            % (node, growth, max_growth))


def counters_list(nodes, counters, died, failures):
    print('counters:')
    for node in nodes:
        lines = counters.get(node)
        if not lines:
            print('  %s: no summary line' % node)
            if node not in died:
                failures.append('%s printed no summary line' % node)
        for line in lines or []:
            print('  %s: %s' % (node, line))


def world_checks(counters, duration, failures):
    """The simulated seconds world_sim ran; fails a short run or one that lost its lockstep."""
    world = ' '.join(counters.get('/world_sim', []))
    m = SIMULATED.search(world)
    simulated = float(m.group(1)) if m else 0.0
    if simulated < duration - 1.0:
        failures.append('world_sim stopped at %.1f s of the %.0f s asked for' % (simulated, duration))
    m = DROPPED.search(world)
    if m and int(m.group(1)) > 0:
        # A participant that kept the world waiting too long (or never started) runs free from
        # then on: the run is no longer the lockstep run asked for.
        failures.append('world_sim dropped %s participants from the lockstep (its log names them)' % m.group(1))
    return simulated


def main():
    a = parse_args()
    failures = []
    nodes = [n for n, _ in read_lines(os.path.join(a.dir, 'pids'))]
    if not nodes:
        failures.append('the monitor found no nodes (see %s)' % a.dir)
    counters, died = read_log(a.log)
    events = read_lines(os.path.join(a.dir, 'events'))
    for sim_s, what, detail in events:
        if what == 'died':
            died.setdefault(detail, 'gone at %s s (simulated) while world_sim ran' % sim_s)
        elif what == 'killed':
            print('soak: killed %s at %s s (simulated), as asked (--kill-node)' % (detail, sim_s))
    flat = [(detail, sim_s) for sim_s, what, detail in events if what == 'flat']

    samples = read_samples(os.path.join(a.dir, 'samples.csv'))
    memory_table(nodes, samples, a.baseline, a.max_growth, failures)
    counters_list(nodes, counters, died, failures)
    simulated = world_checks(counters, a.duration, failures)

    batteries = read_lines(os.path.join(a.dir, 'batteries'))
    print('robots: lowest battery %s' % (', '.join('%s %s' % (r, v) for r, v in batteries) or 'none reported'))
    if not batteries:
        failures.append('no robot reported its battery')
    print('robots flat: %s' % (', '.join('%s at %s s' % f for f in flat) or 'none'))
    for robot, sim_s in flat:
        failures.append('%s ran flat at %s s (simulated)' % (robot, sim_s))
    print('nodes died: %s' % ('; '.join('%s (%s)' % d for d in sorted(died.items())) or 'none'))
    for node, how in sorted(died.items()):
        failures.append('%s died: %s' % (node, how))
    print('wall time: %.0f s for %.0f simulated s (real-time factor %.1f); CPU time of the nodes %.0f s, '
          'of this monitor %.0f s' % (a.wall, simulated, simulated / a.wall if a.wall > 0 else 0.0,
                                     sum(samples[n][-1][2] for n in nodes if n in samples),
                                     samples[MONITOR][-1][2] if MONITOR in samples else 0.0))

    if failures:
        for f in failures:
            print('soak: FAIL: ' + f)
        sys.exit(1)
    print('soak: PASS')


if __name__ == '__main__':
    main()
