"""The report's statistics against published and hand-computed values."""
import math
import os
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))

from coverbench_report import stats  # noqa: E402

EXACT = {"better": -1, "tie_absolute": 0.0, "tie_relative": 0.0}


class Wilcoxon(unittest.TestCase):
    def test_darwins_maize_as_fisher_analysed_it(self):
        # Fisher, The Design of Experiments (1935): Darwin's 15 paired differences (eighths of an
        # inch). Signed-rank statistic W = 24 (the ranks of the two negative differences, 10 + 14),
        # exact two-sided p = 0.0413.
        d = [6, 8, 14, 16, 23, 24, 28, 29, 41, -48, 49, 56, 60, -67, 75]
        r = stats.paired(EXACT, d, [0] * len(d))
        self.assertAlmostEqual(r["p"], 0.041259765625, places=9)
        self.assertEqual((r["wins"], r["ties"], r["losses"]), (2, 0, 13))  # lower is better here
        self.assertEqual(r["median"], 24)
        self.assertLessEqual(r["low"], 24)
        self.assertGreaterEqual(r["high"], 24)

    def test_ties_within_the_band_are_dropped_and_all_ties_give_p_one(self):
        spec = {"better": +1, "tie_absolute": 0.001, "tie_relative": 0.0}
        r = stats.paired(spec, [0.9995, 1.0, 0.5], [1.0, 1.0, 0.4])
        self.assertEqual((r["wins"], r["ties"], r["losses"]), (1, 2, 0))
        self.assertEqual(stats.paired(spec, [1.0, 1.0], [1.0, 0.9999])["p"], 1.0)

    def test_bootstrap_interval_is_reproducible(self):
        d = [0.1, -0.2, 0.3, 0.05, 0.4, -0.1, 0.2]
        a = stats.paired(EXACT, d, [0] * 7)
        b = stats.paired(EXACT, d, [0] * 7)
        self.assertEqual((a["low"], a["high"]), (b["low"], b["high"]))
        self.assertLess(a["low"], a["median"])
        self.assertGreater(a["high"], a["median"])

    def test_bootstrap_interval_does_not_depend_on_the_pairs_order(self):
        # Run keys order the pairs, and a planner's new version changes its keys: the same pairs in
        # another order must give the same interval.
        d = [0.1, -0.2, 0.3, 0.05, 0.4, -0.1, 0.2, 0.7, -0.3]
        a = stats.paired(EXACT, d, [0] * 9)
        b = stats.paired(EXACT, list(reversed(d)), [0] * 9)
        c = stats.paired(EXACT, d[4:] + d[:4], [0] * 9)
        self.assertEqual((a["low"], a["high"]), (b["low"], b["high"]))
        self.assertEqual((a["low"], a["high"]), (c["low"], c["high"]))


class MedianBootstrap(unittest.TestCase):
    """The bootstrap distribution of the median, computed exactly (no resampling)."""

    def test_three_values_by_hand(self):
        # n = 3: the median is at or below the smallest value when 2 or 3 of 3 draws land on it:
        # 3 (1/3)^2 (2/3) + (1/3)^3 = 7/27; by symmetry 7/27 at the largest, 13/27 in the middle.
        support, mass = stats.median_bootstrap([1.0, 2.0, 3.0])
        self.assertEqual(list(support), [1.0, 2.0, 3.0])
        for got, want in zip(mass, [7 / 27, 13 / 27, 7 / 27]):
            self.assertAlmostEqual(got, want, places=15)

    def test_two_values_by_hand(self):
        # n = 2: resamples (0,0), (0,1), (1,0), (1,1): medians 0, 0.5, 0.5, 1.
        support, mass = stats.median_bootstrap([0.0, 1.0])
        self.assertEqual(list(support), [0.0, 0.5, 1.0])
        for got, want in zip(mass, [0.25, 0.5, 0.25]):
            self.assertAlmostEqual(got, want, places=15)

    def test_every_resample_enumerated(self):
        # All n^n resamples of small samples, ties included, odd and even n.
        import itertools
        from collections import Counter
        for x in ([0.0, 0.0, 1.0, 3.0], [2.0, 2.0, 2.0, 5.0, 7.0], [-1.0, 0.5, 0.5, 4.0, 4.0, 9.0],
                  [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7]):
            n = len(x)
            count = Counter()
            for draw in itertools.product(x, repeat=n):
                d = sorted(draw)
                count[d[n // 2] if n % 2 else (d[n // 2 - 1] + d[n // 2]) / 2] += 1
            support, mass = stats.median_bootstrap(x)
            self.assertEqual(list(support), sorted(count))
            for value, p in zip(support, mass):
                self.assertAlmostEqual(p, count[value] / n ** n, places=14)

    def test_interval_is_the_distributions_tail_quantiles(self):
        # With 7/27 > 2.5 % at each end, the 95 % interval of 1, 2, 3 is the whole range.
        self.assertEqual(stats.median_interval([1.0, 2.0, 3.0]), (1.0, 3.0))
        # 41 values 0..40: the interval is the first place whose binomial tail reaches 2.5 % and
        # the last below 97.5 %, by scipy's binomial distribution directly.
        from scipy.stats import binom
        x = [float(k) for k in range(41)]
        cdf = [binom.sf(20, 41, (j + 1) / 41) for j in range(41)]
        lo = next(j for j in range(41) if cdf[j] >= 0.025)
        hi = next(j for j in range(41) if cdf[j] >= 0.975)
        self.assertEqual(stats.median_interval(x), (float(lo), float(hi)))
        self.assertLess(lo, 20)
        self.assertGreater(hi, 20)


class Friedman(unittest.TestCase):
    def test_identical_rankings_by_hand(self):
        # 4 walls, 3 planners, every wall ranks them 1, 2, 3 (lower is better): rank sums 4, 8, 12,
        # chi2 = 12 / (n k (k+1)) * sum R^2 - 3 n (k+1) = 12/48 * 224 - 48 = 8, p = exp(-8/2).
        table = [[1, 2, 3], [10, 20, 30], [0.1, 0.5, 0.9], [5, 6, 7]]
        r = stats.friedman(EXACT, table)
        self.assertAlmostEqual(r["statistic"], 8.0)
        self.assertAlmostEqual(r["p"], math.exp(-4.0))
        self.assertEqual(r["ranks"], [1.0, 2.0, 3.0])

    def test_nemenyi_q_values_of_demsar_2006(self):
        # Demsar (2006), JMLR 7, Table 5(a): q_0.05 for k = 2..10 (critical difference with N = 6
        # blocks is q * sqrt(k (k+1) / (6 N)) = q * sqrt(k (k+1)) / 6).
        published = [1.960, 2.343, 2.569, 2.728, 2.850, 2.949, 3.031, 3.102, 3.164]
        for k, q in zip(range(2, 11), published):
            self.assertAlmostEqual(stats.nemenyi_cd(k, 6) * 6 / math.sqrt(k * (k + 1)), q, delta=0.0015)


class Holm(unittest.TestCase):
    def test_step_down_by_hand(self):
        # sorted 0.005, 0.01, 0.03, 0.04 times 4, 3, 2, 1 = 0.02, 0.03, 0.06, 0.04 -> running max
        # 0.02, 0.03, 0.06, 0.06; back in input order:
        self.assertEqual(stats.holm([0.01, 0.04, 0.03, 0.005]), [0.03, 0.06, 0.06, 0.02])
        adjusted = stats.holm([0.5, math.nan, 0.9])
        self.assertEqual(adjusted[0], 1.0)
        self.assertTrue(math.isnan(adjusted[1]))


class Wilson(unittest.TestCase):
    def test_newcombe_1998(self):
        # Newcombe (1998), Statistics in Medicine 17, Table I: 81/263, Wilson 0.2553 to 0.3662.
        low, high = stats.wilson(81, 263)
        self.assertAlmostEqual(low, 0.2553, places=4)
        self.assertAlmostEqual(high, 0.3662, places=4)
        self.assertTrue(all(math.isnan(x) for x in stats.wilson(0, 0)))


class PerformanceProfile(unittest.TestCase):
    def test_by_hand(self):
        # ratios to the best per problem: [1, 2], [1, 1], [1, inf]
        rho, ratio = stats.performance_profile([[1, 2], [3, 3], [2, math.inf]], [1.0, 2.0, 100.0])
        self.assertEqual(ratio.tolist(), [[1, 2], [1, 1], [1, math.inf]])
        self.assertEqual(rho[0].tolist(), [1, 1, 1])
        self.assertEqual(rho[1].tolist(), [1 / 3, 2 / 3, 2 / 3])  # a failure never reaches any tau

    def test_a_problem_everyone_failed_counts_against_all(self):
        rho, _ = stats.performance_profile([[1, 1], [math.inf, math.inf]], [1.0, 10.0])
        self.assertEqual(rho.tolist(), [[0.5, 0.5], [0.5, 0.5]])


class PowerLaw(unittest.TestCase):
    def test_recovers_an_exponent(self):
        x = [1, 2, 4, 8, 16]
        fit = stats.power_law(x, [3 * v ** 1.5 for v in x])
        self.assertAlmostEqual(fit["exponent"], 1.5)
        self.assertIsNone(stats.power_law([1, 1, 2], [1, 2, 3]))


if __name__ == "__main__":
    unittest.main()
