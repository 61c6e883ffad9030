#!/usr/bin/env python3
"""Tests of compare.py's pairing of esmini's rows with Corsa's trajectory rows."""

import os
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import compare  # noqa: E402


def trajectory(*rows):
    """compare.read_trajectory's form from (time s, entity, x, y) rows."""
    table = {}
    for time, name, x, y in rows:
        table.setdefault((round(time * 1e6), name), []).append((x, y, 0.0, 0.0))
    return table


class GhostRunNames(unittest.TestCase):
    def test_a_row_of_an_earlier_ghost_run_is_paired_with_the_ghost_at_its_time(self):
        corsa = trajectory((1.01, 'Ego_ghost', 65.100, -11.500),
                           (1.01, 'Ego_ghost', 65.023, -10.625))
        rows, earlier = compare.rows_for(corsa, 1.01, 'Ego_ghost_-1')
        self.assertTrue(earlier)
        self.assertEqual([(65.100, -11.500), (65.023, -10.625)], [r[:2] for r in rows])

    def test_the_second_restart_s_run_maps_to_the_same_ghost(self):
        corsa = trajectory((5.01, 'Car_ghost', 78.5, 0.0))
        rows, earlier = compare.rows_for(corsa, 5.01, 'Car_ghost_-2')
        self.assertTrue(earlier)
        self.assertEqual(78.5, rows[0][0])

    def test_a_name_corsa_records_is_taken_as_it_is(self):
        corsa = trajectory((2.0, 'Car_-1', 1.0, 2.0), (2.0, 'Car', 9.0, 9.0))
        rows, earlier = compare.rows_for(corsa, 2.0, 'Car_-1')
        self.assertFalse(earlier)
        self.assertEqual(1.0, rows[0][0])

    def test_other_names_and_times_find_nothing(self):
        corsa = trajectory((1.0, 'Ego_ghost', 0.0, 0.0))
        self.assertEqual((None, False), compare.rows_for(corsa, 1.01, 'Ego_ghost_-1'))
        self.assertEqual((None, False), compare.rows_for(corsa, 1.0, 'Ego_ghost_-0'))
        self.assertEqual((None, False), compare.rows_for(corsa, 1.0, 'Ego_ghost_1'))
        self.assertEqual((None, False), compare.rows_for(corsa, 1.0, 'Other_-1'))


if __name__ == '__main__':
    unittest.main()
