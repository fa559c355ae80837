"""Statistics for reports: every test and interval comes from scipy.stats; what is computed here
is only the bookkeeping around them (pairing, tie bands, Holm's step-down, profile ratios)."""
import math

import numpy as np
from scipy import stats

ALPHA = 0.05
BOOTSTRAP_RESAMPLES = 2000
BOOTSTRAP_SEED = 20261123  # fixed: the same results give the same intervals, byte for byte


def wilson(successes, trials, confidence=0.95):
    """Wilson score interval of a proportion (scipy.stats.binomtest)."""
    if trials == 0:
        return (math.nan, math.nan)
    ci = stats.binomtest(successes, trials).proportion_ci(confidence_level=confidence, method="wilson")
    return (float(ci.low), float(ci.high))


def holm(pvalues):
    """Holm's step-down adjusted p-values, in the input order (NaN stays NaN, not counted)."""
    indexed = [(p, i) for i, p in enumerate(pvalues) if not math.isnan(p)]
    indexed.sort()
    m = len(indexed)
    adjusted = [math.nan] * len(pvalues)
    running = 0.0
    for rank, (p, i) in enumerate(indexed):
        running = max(running, min(1.0, (m - rank) * p))
        adjusted[i] = running
    return adjusted


def tied(spec, a, b):
    """Whether two values are equal within the metric's tie band (same rule as the C++ registry)."""
    if a == b:
        return True
    if not (math.isfinite(a) and math.isfinite(b)):  # a failure (infinite) ties nothing but a failure
        return False
    return abs(a - b) <= spec["tie_absolute"] + spec["tie_relative"] * max(abs(a), abs(b))


def paired(spec, values, baseline):
    """Paired comparison of `values` against `baseline` (equal-length lists, one pair per wall).

    A failure (no valid path) is the metric's worst value, infinite (analysis.Analysis.pairs): it
    loses to every value. Returns pairs, wins/ties/losses (better = the metric's direction, ties
    within its band), `failed` and `baseline_failed` (pairs where that side failed), the median
    difference (values - baseline) with a percentile bootstrap 95 % interval over the pairs where
    both have a value (`both`), and the two-sided Wilcoxon signed-rank p-value over the pairs that
    are not tied (1 when all are), a failure's difference ranked above every finite one (failures
    share the largest rank)."""
    a = np.asarray(values, dtype=float)
    b = np.asarray(baseline, dtype=float)
    n = len(a)
    out = {"pairs": n, "wins": 0, "ties": 0, "losses": 0, "failed": int((~np.isfinite(a)).sum()),
           "baseline_failed": int((~np.isfinite(b)).sum()), "both": 0, "median": math.nan, "low": math.nan,
           "high": math.nan, "p": math.nan}
    if n == 0:
        return out
    finite = np.isfinite(a) & np.isfinite(b)
    with np.errstate(invalid="ignore"):
        diff = a - b  # +-inf where one side failed (never both: such walls are not pairs)
    tie = np.array([tied(spec, x, y) for x, y in zip(a, b)])
    better = spec["better"]
    out["ties"] = int(tie.sum())
    out["wins"] = int(((diff * better > 0) & ~tie).sum())
    out["losses"] = int(((diff * better < 0) & ~tie).sum())
    both = diff[finite]
    out["both"] = int(len(both))
    if len(both):
        out["median"] = float(np.median(both))
    if len(both) >= 2 and np.ptp(both) > 0:
        # Resampled from the sorted differences: the interval is a function of the pairs, not of
        # the order they were read in (run keys, which change with a planner's version).
        res = stats.bootstrap((np.sort(both),), np.median, n_resamples=BOOTSTRAP_RESAMPLES, vectorized=True,
                              method="percentile", random_state=np.random.default_rng(BOOTSTRAP_SEED))
        out["low"], out["high"] = float(res.confidence_interval.low), float(res.confidence_interval.high)
    else:
        out["low"] = out["high"] = out["median"]
    untied = diff[~tie]
    if len(untied) == 0:
        out["p"] = 1.0
    else:
        # Only the ranks of |difference| matter: a failure's stands above every finite one.
        big = 2.0 * float(np.max(np.abs(untied[np.isfinite(untied)]), initial=0.0)) + 1.0
        untied = np.where(np.isfinite(untied), untied, np.sign(untied) * big)
        out["p"] = float(stats.wilcoxon(untied, zero_method="wilcox", alternative="two-sided").pvalue)
    return out


def nemenyi_cd(k, blocks, alpha=ALPHA):
    """Nemenyi's critical difference of average ranks for k treatments over `blocks` blocks
    (Demsar 2006): q_alpha / sqrt(2) * sqrt(k (k + 1) / (6 N)), q from the studentized range."""
    q = stats.studentized_range.ppf(1 - alpha, k, np.inf) / math.sqrt(2)
    return float(q * math.sqrt(k * (k + 1) / (6.0 * blocks)))


def friedman(spec, table):
    """Friedman test over a blocks x treatments table (rows: walls, columns: planners).

    Returns the statistic, p-value, the average ranks (1 = best in the metric's direction, ties
    averaged) and Nemenyi's critical difference."""
    data = np.asarray(table, dtype=float)
    n, k = data.shape
    oriented = -data * spec["better"]  # smaller is better after orientation
    ranks = np.apply_along_axis(stats.rankdata, 1, oriented)
    out = {"blocks": n, "k": k, "ranks": [float(r) for r in ranks.mean(axis=0)], "statistic": math.nan,
           "p": math.nan, "cd": math.nan}
    if n < 2 or k < 3:
        return out
    if np.all(data == data[:, :1]):
        out["statistic"], out["p"] = 0.0, 1.0
    else:
        res = stats.friedmanchisquare(*[data[:, j] for j in range(k)])
        out["statistic"], out["p"] = float(res.statistic), float(res.pvalue)
    out["cd"] = nemenyi_cd(k, n)
    return out


def performance_profile(costs, taus):
    """Dolan-More performance profiles. `costs`: problems x solvers, inf for a failure.

    rho_s(tau) = share of problems where solver s's cost is within tau times the best cost.
    A problem every solver failed counts against all of them."""
    c = np.asarray(costs, dtype=float)
    best = np.min(c, axis=1, keepdims=True)
    with np.errstate(invalid="ignore", divide="ignore"):
        ratio = np.where(np.isfinite(c), c / best, np.inf)
    ratio[~np.isfinite(best[:, 0]), :] = np.inf
    return np.array([[float(np.mean(ratio[:, s] <= t)) for t in taus] for s in range(c.shape[1])]), ratio


def power_law(x, y):
    """Least-squares fit of log y = a + b log x (scipy.stats.linregress): exponent b, its
    standard error and r; None with fewer than 3 distinct x."""
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    keep = (x > 0) & (y > 0) & np.isfinite(x) & np.isfinite(y)
    if len(np.unique(x[keep])) < 3:
        return None
    r = stats.linregress(np.log10(x[keep]), np.log10(y[keep]))
    return {"exponent": float(r.slope), "stderr": float(r.stderr), "intercept": float(r.intercept),
            "r": float(r.rvalue), "n": int(keep.sum())}


def geometric_mean_ci(log_ratios, confidence=0.95):
    """Geometric mean of ratios from their logarithms, with a t-interval on the mean log ratio
    (scipy.stats.t), taken back by exp: (mean, low, high). One ratio gives no interval (NaN); equal
    ratios give an interval of width zero."""
    x = np.asarray(log_ratios, dtype=float)
    n = len(x)
    if n == 0:
        return (math.nan, math.nan, math.nan)
    mean = float(np.mean(x))
    if n == 1:
        return (_exp(mean), math.nan, math.nan)
    half = float(stats.t.ppf(0.5 + confidence / 2, n - 1)) * float(np.std(x, ddof=1)) / math.sqrt(n)
    return (_exp(mean), _exp(mean - half), _exp(mean + half))


def _exp(v):
    """e^v, infinity past the largest double (a ratio of over 1e308)."""
    try:
        return math.exp(v)
    except OverflowError:
        return math.inf


def signed_rank(log_ratios):
    """Two-sided Wilcoxon signed-rank p-value of log ratios against 0 (scipy.stats.wilcoxon);
    NaN without any, 1 when every ratio is 1."""
    x = np.asarray(log_ratios, dtype=float)
    if len(x) == 0:
        return math.nan
    if np.all(x == 0):
        return 1.0
    return float(stats.wilcoxon(x, zero_method="wilcox", alternative="two-sided").pvalue)
