#!/usr/bin/python3
"""launch/team_robots.launch as roslaunch reads it, without starting anything: each robot's
nodes on that robot's <machine> (address, user, env-loader as given), its robot_id and seed, for
every task; localhost needs no ssh; bad arguments stop the launch naming what is wrong.

Run with the workspace's devel/setup.bash sourced (ctest does, through scripts/test.sh)."""
import os
import unittest

import roslaunch.config
import roslaunch.core
import rospkg

LAUNCH = os.path.join(rospkg.RosPack().get_path('multirobot_audio'), 'launch', 'team_robots.launch')
# Documentation addresses (RFC 5737): never this machine, and never looked up.
HOSTS = ['192.0.2.10', '192.0.2.11', '192.0.2.12']
IDS = [11, 30, 212]
TASK_NODES = {
    'wanderer': ['nava_modem', 'wanderer'],
    'mutex': ['nava_modem', 'local_mutex'],
    'charging': ['nava_modem', 'local_mutex', 'charging_demo'],
}


def load(*args):
    """The launch's configuration with nodes assigned to machines, as roslaunch would run it."""
    return roslaunch.config.load_config_default([(LAUNCH, list(args))], None)


def remote_team(task):
    return load('hosts:=' + ' '.join(HOSTS), 'task:=' + task, 'ids:=' + ' '.join(str(i) for i in IDS),
                'user:=robot', 'env_loader:=/opt/team/robot_env.sh', 'ssh_port:=2222', 'chargers:=[100]')


class TeamRobotsMachines(unittest.TestCase):

    def test_each_robot_runs_its_task_on_its_own_machine(self):
        for task, node_types in TASK_NODES.items():
            with self.subTest(task=task):
                config = remote_team(task)
                expected = sorted('/robot_%d/%s' % (k, t) for k in range(len(HOSTS)) for t in node_types)
                self.assertEqual(sorted(n.namespace + n.name for n in config.nodes), expected)
                for n in config.nodes:
                    k = int(n.namespace.strip('/').split('_')[1])
                    m = n.machine
                    self.assertEqual((m.name, m.address, m.user, m.env_loader, m.ssh_port),
                                     ('robot_%d' % k, HOSTS[k], 'robot', '/opt/team/robot_env.sh', 2222),
                                     n.namespace + n.name)
                self.assertTrue(config.has_remote_nodes())

    def test_robot_ids_and_seeds_follow_ids(self):
        config = remote_team('charging')
        for k, robot_id in enumerate(IDS):
            self.assertEqual(config.params['/robot_%d/local_mutex/robot_id' % k].value, robot_id)
            for node in ('nava_modem', 'local_mutex', 'charging_demo'):
                self.assertEqual(config.params['/robot_%d/%s/seed' % (k, node)].value, robot_id, node)

    def test_without_ids_robot_k_is_number_k_plus_1(self):
        config = load('hosts:=' + ' '.join(HOSTS[:2]), 'task:=mutex')
        self.assertEqual(config.params['/robot_0/local_mutex/robot_id'].value, 1)
        self.assertEqual(config.params['/robot_1/local_mutex/robot_id'].value, 2)
        self.assertEqual(config.params['/robot_1/nava_modem/seed'].value, 2)

    def test_localhost_robots_run_here_without_ssh(self):
        config = load('hosts:=localhost localhost localhost')
        self.assertEqual(len(config.nodes), 6)
        self.assertTrue(all(roslaunch.core.is_machine_local(n.machine) for n in config.nodes))
        self.assertFalse(config.has_remote_nodes())

    def test_bad_arguments_stop_the_launch(self):
        for args, words in [(['hosts:=a', 'task:=explore'], 'task_must_be_wanderer_mutex_or_charging'),
                            (['hosts:=a b c', 'ids:=11 30'], 'ids_must_give_one_id_per_host'),
                            (['hosts:=a', 'task:=charging'], "'chargers'")]:
            with self.subTest(args=args):
                with self.assertRaisesRegex(roslaunch.core.RLException, words):
                    load(*args)


if __name__ == '__main__':
    unittest.main()
