#!/usr/bin/env python3
"""Tests of compare.py's pairing of esmini's rows with Corsa's trajectory rows."""

import os
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import compare  # noqa: E402


def trajectory(*rows):
    """compare.trajectory_table of (time s, entity, x, y) rows in recording order."""
    return compare.trajectory_table((time, name, x, y, 0.0, 0.0) for time, name, x, y in rows)


def positions(rows):
    return [r[:2] for r in rows]


class GhostRunNames(unittest.TestCase):
    def test_a_row_of_an_earlier_ghost_run_is_paired_with_the_ghost_s_run_before_the_restart(self):
        corsa = trajectory((1.00, 'Ego_ghost', 65.000, -11.500),
                           (1.01, 'Ego_ghost', 65.100, -11.500),
                           (0.52, 'Ego_ghost', 60.000, -10.000),
                           (1.01, 'Ego_ghost', 65.023, -10.625))
        rows, earlier = compare.rows_for(corsa, 1.01, 'Ego_ghost_-1')
        self.assertTrue(earlier)
        self.assertEqual([(65.100, -11.500)], positions(rows))
        # The ghost's own name keeps both rows of that time (the smoke test accepts either).
        rows, earlier = compare.rows_for(corsa, 1.01, 'Ego_ghost')
        self.assertFalse(earlier)
        self.assertEqual([(65.100, -11.500), (65.023, -10.625)], positions(rows))

    def test_the_earlier_run_is_taken_even_when_the_later_run_is_nearer(self):
        # esmini's Car_ghost_-1 at 3.01 s is at (67.2, -1.535): the later run's row is the nearer
        # one, yet the row belongs to the run before the first restart.
        corsa = trajectory((3.01, 'Car_ghost', 70.100, -1.535),
                           (1.02, 'Car_ghost', 50.200, -1.535),
                           (3.01, 'Car_ghost', 67.229, -1.535))
        rows, earlier = compare.rows_for(corsa, 3.01, 'Car_ghost_-1')
        self.assertTrue(earlier)
        self.assertEqual([(70.100, -1.535)], positions(rows))

    def test_the_second_restart_s_run_is_the_run_between_the_two_restarts(self):
        corsa = trajectory((3.01, 'Car_ghost', 70.100, -1.535),
                           (5.01, 'Car_ghost', 90.000, -1.535),
                           (1.02, 'Car_ghost', 50.200, -1.535),
                           (5.01, 'Car_ghost', 78.643, -1.535),
                           (3.02, 'Car_ghost', 67.300, -1.535),
                           (5.01, 'Car_ghost', 71.541, -1.535))
        rows, earlier = compare.rows_for(corsa, 5.01, 'Car_ghost_-2')
        self.assertTrue(earlier)
        self.assertEqual([(78.643, -1.535)], positions(rows))
        rows, earlier = compare.rows_for(corsa, 5.01, 'Car_ghost_-1')
        self.assertEqual([(90.000, -1.535)], positions(rows))
        # No third restart: the run after the second one is Car_ghost's own.
        self.assertEqual((None, False), compare.rows_for(corsa, 5.01, 'Car_ghost_-3'))

    def test_a_ghost_corsa_did_not_restart_has_no_earlier_run(self):
        corsa = trajectory((3.00, 'Car_ghost', 69.100, -1.535),
                           (3.01, 'Car_ghost', 70.100, -1.535))
        self.assertEqual((None, False), compare.rows_for(corsa, 3.01, 'Car_ghost_-1'))

    def test_a_run_without_a_row_at_that_time_finds_nothing(self):
        # Run 0 ended at 3.01 s; only run 1 reached 4.00 s.
        corsa = trajectory((3.01, 'Car_ghost', 70.100, -1.535),
                           (1.02, 'Car_ghost', 50.200, -1.535),
                           (4.00, 'Car_ghost', 75.000, -1.535))
        self.assertEqual((None, False), compare.rows_for(corsa, 4.00, 'Car_ghost_-1'))

    def test_a_non_ghost_s_earlier_run_name_is_not_mapped(self):
        corsa = trajectory((3.01, 'Foo', 70.100, -1.535),
                           (1.02, 'Foo', 50.200, -1.535),
                           (3.01, 'Foo', 67.229, -1.535))
        self.assertEqual((None, False), compare.rows_for(corsa, 3.01, 'Foo_-1'))

    def test_a_name_corsa_records_is_taken_as_it_is(self):
        corsa = trajectory((2.0, 'Car_-1', 1.0, 2.0), (2.0, 'Car', 9.0, 9.0),
                           (2.0, 'Car_ghost_-1', 3.0, 4.0), (2.0, 'Car_ghost', 8.0, 8.0))
        rows, earlier = compare.rows_for(corsa, 2.0, 'Car_-1')
        self.assertFalse(earlier)
        self.assertEqual([(1.0, 2.0)], positions(rows))
        rows, earlier = compare.rows_for(corsa, 2.0, 'Car_ghost_-1')
        self.assertFalse(earlier)
        self.assertEqual([(3.0, 4.0)], positions(rows))

    def test_other_names_and_times_find_nothing(self):
        corsa = trajectory((1.0, 'Ego_ghost', 0.0, 0.0))
        self.assertEqual((None, False), compare.rows_for(corsa, 1.01, 'Ego_ghost_-1'))
        self.assertEqual((None, False), compare.rows_for(corsa, 1.0, 'Ego_ghost_-0'))
        self.assertEqual((None, False), compare.rows_for(corsa, 1.0, 'Ego_ghost_1'))
        self.assertEqual((None, False), compare.rows_for(corsa, 1.0, 'Other_-1'))


ALKS_SUITE = r"""
ESMINI_PATH = '../'
COMMON_ARGS = '--headless --fixed_timestep 0.05 --record sim.dat '
ALKS_PREFIX = './OSC-ALKS-scenarios/Scenarios/'


class TestSuite(unittest.TestCase):

    def test_ALKS_Scenario_4_4_2_CutInUnavoidableCollision(self):
        log = run_scenario(os.path.join(ALKS_PREFIX + 'ALKS_Scenario_4.4_2_CutIn.xosc'), COMMON_ARGS)
        self.assertTrue(re.search('9.10.* CutInStartCondition == true, rel_dist: 10.00 < 10.00', log))
        csv = generate_csv()
        self.assertTrue(re.search('\n8.00.*, 0, Ego, 138.33.*, -8.00.*, 0.00.*, 0.00.*, 0.00.*, 0.00.*, 16.6[67].*,.*', csv))
        self.assertTrue(re.search('\n9.600, 1, CutInVehicle, 177.185, -10.896, 0.000, 0.189, 0.000, 0.000, 11.111, 0.099, 3.169', csv))

    def test_unit(self):
        log = run_scenario(os.path.join(ESMINI_PATH, 'EnvironmentSimulator/Unittest/xosc/a.xosc'), COMMON_ARGS)
        csv = generate_csv()
        self.assertTrue(re.search('\n1.000, 0, Car, 5.000, -1.535, 0.000, 0.000, 0.000, 0.000, 10.000', csv))
"""


class SuiteSources(unittest.TestCase):
    """Rows of a test written as esmini's alks_suite.py: scenarios named by a prefix variable."""

    def rows(self):
        with tempfile.TemporaryDirectory() as folder:
            path = os.path.join(folder, 'alks_suite.py')
            with open(path, 'w', encoding='utf-8') as f:
                f.write(ALKS_SUITE)
            return compare.read_smoke_rows(path)

    def test_a_scenario_joined_to_a_prefix_variable_is_that_path_inside_the_alks_repository(self):
        rows = self.rows()
        self.assertEqual(['OSC-ALKS-scenarios/Scenarios/ALKS_Scenario_4.4_2_CutIn.xosc'] * 2 +
                         ['EnvironmentSimulator/Unittest/xosc/a.xosc'], [r.scenario for r in rows])
        self.assertEqual((0.05, []), compare.corsa_options(rows[0].esmini_args))

    def test_a_digit_class_and_the_pattern_s_tail_are_read_as_the_first_digit(self):
        row = self.rows()[0]
        self.assertEqual((8.0, 'Ego', 138.33, -8.0, 0.0, 16.66),
                         (row.time, row.name, row.x, row.y, row.h, row.speed))
        row = self.rows()[1]
        self.assertEqual((9.6, 'CutInVehicle', 177.185, -10.896, 0.189, 11.111),
                         (row.time, row.name, row.x, row.y, row.h, row.speed))

    def test_a_path_in_the_alks_repository_is_found_in_its_copy_any_other_in_the_kit(self):
        self.assertEqual(os.path.join('/alks', 'Scenarios', 'A.xosc'),
                         compare.scenario_file('OSC-ALKS-scenarios/Scenarios/A.xosc', '/kit', '/alks'))
        self.assertEqual(os.path.join('/kit', 'resources', 'xosc', 'A.xosc'),
                         compare.scenario_file('resources/xosc/A.xosc', '/kit', '/alks'))


class TrajectoryRuns(unittest.TestCase):
    def test_an_entity_s_run_counts_its_rewinds_in_recording_order(self):
        corsa = trajectory((0.0, 'A', 0.0, 0.0), (1.0, 'A', 1.0, 0.0), (0.5, 'A', 2.0, 0.0),
                           (1.0, 'A', 3.0, 0.0), (0.0, 'B', 9.0, 0.0))
        self.assertEqual([0, 1], [r[4] for r in corsa[(1000000, 'A')]])
        self.assertEqual([1], [r[4] for r in corsa[(500000, 'A')]])
        self.assertEqual([0], [r[4] for r in corsa[(0, 'B')]])
        self.assertEqual({'A': 1}, corsa.rewinds)

    def test_the_rows_after_a_rewind_stay_in_its_run_until_the_next_rewind(self):
        corsa = trajectory((2.0, 'A', 0.0, 0.0), (3.0, 'A', 0.0, 0.0), (1.0, 'A', 1.0, 0.0),
                           (2.0, 'A', 1.0, 0.0), (3.0, 'A', 1.0, 0.0), (4.0, 'A', 1.0, 0.0),
                           (2.5, 'A', 2.0, 0.0), (3.0, 'A', 2.0, 0.0))
        self.assertEqual([0, 1, 2], [r[4] for r in corsa[(3000000, 'A')]])
        self.assertEqual([1], [r[4] for r in corsa[(4000000, 'A')]])
        self.assertEqual({'A': 2}, corsa.rewinds)


if __name__ == '__main__':
    unittest.main()
